#pragma once
// Internal: a vehicle body lofted through its plan, side and section profiles. The plan is a
// superellipse |x / a|^p + |y / b|^p = 1; each station x has a cross-section whose half width
// follows the flank (bulging, rounded at the sill), steps in at the shoulder (the belt line) and
// leans in up the glass (tumblehome) to a rounded roof edge and a crowned roof. Wheel arches cut
// the underside. Windows, pillars, trim, lamps, grille, plates, mirrors, door seams and handles,
// and a cabin with seats seen through the glass, are added on top. The actor frame: x forward,
// y left, z up, the origin on the ground under the middle of the footprint.
#include <vector>

#include "loft.h"

namespace flowscape::assets {

// Material slots of the vehicle models; a part's `materials` maps them to the actor's materials.
enum Slot : std::uint16_t {
  kPaint,
  kGlass,
  kTrim,  // black plastic: bumpers' lower parts, pillars, seals, mirrors' housings
  kChrome,
  kHeadLamp,
  kTailLamp,
  kIndicator,
  kPlate,
  kInterior,
  kUnderbody,
  kTyre,
  kRim,
  kGrille,
  kLivery,  // a second colour: taxi signs, police stripes, a delivery van's band
  kSkin,    // riders and drivers (people.h)
  kMarker,  // a truck's marker lamps: amber along its sides, at the front top corners
  kSlotCount
};

// Where windows are along the body, in x (metres) from its centre.
struct Glazing {
  double windscreen_front = 0, windscreen_back = 0;  // the top is glass between them
  double rear_front = 0, rear_back = 0;              // the rear window on the top
  double side_front = 0, side_back = 0;              // side windows between them
  std::vector<std::pair<double, double>> pillars;    // painted over the side windows
  bool front_face = false, rear_face = false;        // upright glass on the front / rear face (bus)
  double frame = 0.05;                               // black frame round the side glass (m)
};

// A lamp or a plate on the front or rear face (y, z of its centre, half sizes), or a door seam.
struct Decal {
  double y, z, half_width, half_height;
  Slot slot;
};

// A panel on a flank between x0 and x1, z0 and z1 (a bus's door glass, a livery band); side +1
// left, -1 right, 0 both.
struct Panel {
  double x0, x1, z0, z1;
  int side;
  Slot slot;
};

struct BodyShape {
  double length = 4.5, width = 1.8;
  double plan_exponent = 8;  // 2: round, 10: boxy
  Curve top, belt, bottom;   // z over x
  double tumblehome = 0.12, bulge = 0.04, shoulder = 0.04;
  double roof_radius = 0.08, sill_radius = 0.08, crown = 0.03;
  double trim_height = 0.1;   // black trim along the bottom of the flanks
  std::vector<double> axles;  // x of the wheel centres
  double wheel_radius = 0.32, arch_clearance = 0.05;
  Glazing glazing;
  std::vector<Decal> front, rear;  // lamps, grille, plates on the faces
  std::vector<double> seams;       // door seams: x positions on both flanks
  std::vector<double> handles;     // door handles: x positions, just below the belt
  std::vector<Panel> panels;
  bool mirrors = true, cabin = true;
  bool left_hand_drive = true;  // the driver's seat on the left (+y)
};

// The half width of the section at station x and height z (0 outside the body there), and the
// heights the section spans at x.
struct BodyFrame {
  const BodyShape& shape;
  double plan_half_width(double x) const;
  double bottom(double x) const;  // the underside, raised over the wheel arches
  double belt(double x) const;    // min(belt line, top)
  double top(double x) const;
  double half_width(double x, double z) const;
  // x of the front (or rear: -1) surface at (y, z), found by bisection; NaN where none
  double face_x(double y, double z, int end) const;
};

// The body shell (paint, glass, trim, underbody), its decals, mirrors and cabin, in slots.
Mesh vehicle_body(const BodyShape& shape);

// A road wheel: tyre with sidewalls and tread, a rim with a recessed face (the rim material draws
// spokes) and a hub, about the y axis through the origin. `outward`: +1 when the outer face looks
// along +y (a left wheel), -1 for a right one.
Mesh road_wheel(double radius, double width, double rim_share, int outward);

}  // namespace flowscape::assets
