// LD_PRELOAD for memcheck_test.sh: every ray and packet handed to Embree is checked, under
// valgrind's memcheck, to be defined in every byte of every lane (active or not) before Embree
// traces it, so that a partly filled packet is an error wherever Embree would only read it.
#include <dlfcn.h>
#include <embree3/rtcore.h>
#include <valgrind/memcheck.h>

namespace {

template <class Function>
Function embree(const char* name) {
  return reinterpret_cast<Function>(dlsym(RTLD_NEXT, name));
}

template <class T>
void require_defined(const T* bytes) {
  VALGRIND_CHECK_MEM_IS_DEFINED(bytes, sizeof(T));
}

// The context's fields (not the padding between them, which is no value).
void require_defined(const RTCIntersectContext* context) {
  require_defined(&context->flags), require_defined(&context->filter);
  require_defined(&context->instID);
}

void require_defined_lanes(const int* valid, int lanes) {
  VALGRIND_CHECK_MEM_IS_DEFINED(valid, sizeof(int) * lanes);
}

}  // namespace

extern "C" {

void rtcIntersect1(RTCScene scene, RTCIntersectContext* context, RTCRayHit* rayhit) {
  require_defined(context), require_defined(rayhit);
  static const auto next = embree<decltype(&rtcIntersect1)>("rtcIntersect1");
  next(scene, context, rayhit);
}

void rtcOccluded1(RTCScene scene, RTCIntersectContext* context, RTCRay* ray) {
  require_defined(context), require_defined(ray);
  static const auto next = embree<decltype(&rtcOccluded1)>("rtcOccluded1");
  next(scene, context, ray);
}

void rtcIntersect16(const int* valid, RTCScene scene, RTCIntersectContext* context,
                    RTCRayHit16* rayhit) {
  require_defined_lanes(valid, 16), require_defined(context), require_defined(rayhit);
  static const auto next = embree<decltype(&rtcIntersect16)>("rtcIntersect16");
  next(valid, scene, context, rayhit);
}

void rtcOccluded16(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRay16* ray) {
  require_defined_lanes(valid, 16), require_defined(context), require_defined(ray);
  static const auto next = embree<decltype(&rtcOccluded16)>("rtcOccluded16");
  next(valid, scene, context, ray);
}

void rtcSetGeometryTransform(RTCGeometry geometry, unsigned int time_step, RTCFormat format,
                             const void* transform) {
  VALGRIND_CHECK_MEM_IS_DEFINED(transform, 12 * sizeof(float));  // every 3x4 format's floats
  static const auto next = embree<decltype(&rtcSetGeometryTransform)>("rtcSetGeometryTransform");
  next(geometry, time_step, format, transform);
}

}  // extern "C"
