"""A TensorFlow.js graph model (model.json + weight shards) run with PyTorch on the CPU.

Only the operations the pinned detectors use are known; any other is refused by name. Tensors keep
TensorFlow's NHWC layout between operations; convolutions and pooling switch to torch's NCHW and back.
"""
import base64
import json
import math
import os

import numpy as np
import torch
import torch.nn.functional as F

_DTYPES = {"float32": np.float32, "int32": np.int32, "bool": np.bool_}


def _read_weights(model_dir, manifest):
    weights = {}
    for group in manifest:
        blob = b"".join(open(os.path.join(model_dir, p), "rb").read() for p in group["paths"])
        offset = 0
        for spec in group["weights"]:
            count = int(np.prod(spec["shape"])) if spec["shape"] else 1
            quant = spec.get("quantization")
            if quant and quant["dtype"] == "float16":
                raw = np.frombuffer(blob, np.float16, count, offset).astype(np.float32)
                offset += 2 * count
            elif quant and quant["dtype"] == "uint8":
                raw = np.frombuffer(blob, np.uint8, count, offset) * quant["scale"] + quant["min"]
                offset += count
            else:
                dtype = _DTYPES[spec["dtype"]]
                raw = np.frombuffer(blob, dtype, count, offset)
                offset += raw.itemsize * count
            weights[spec["name"]] = torch.from_numpy(
                np.array(raw, dtype=_DTYPES[spec["dtype"]]).reshape(spec["shape"]))
        if offset != len(blob):
            raise ValueError(f"{model_dir}: weight shards hold {len(blob)} bytes, manifest {offset}")
    return weights


def _ints(attr, key):
    return [int(i) for i in attr[key]["list"].get("i", [])]


def _string(attr, key):
    return base64.b64decode(attr[key]["s"]).decode()


def _same_pads(size, kernel, stride, dilation):
    out = math.ceil(size / stride)
    total = max((out - 1) * stride + (kernel - 1) * dilation + 1 - size, 0)
    return total // 2, total - total // 2


def _pad_same(x_nchw, kernel_hw, strides, dilations, value=0.0):
    top, bottom = _same_pads(x_nchw.shape[2], kernel_hw[0], strides[0], dilations[0])
    left, right = _same_pads(x_nchw.shape[3], kernel_hw[1], strides[1], dilations[1])
    return F.pad(x_nchw, (left, right, top, bottom), value=value)


def _conv(attr, x, w, depthwise):
    """TF Conv2D / DepthwiseConv2dNative, NHWC in and out; w is HWIO (depthwise: HW, in, mult)."""
    strides, dilations = _ints(attr, "strides")[1:3], _ints(attr, "dilations")[1:3]
    xc = x.permute(0, 3, 1, 2)
    kh, kw = w.shape[0], w.shape[1]
    if _string(attr, "padding") == "SAME":
        xc = _pad_same(xc, (kh, kw), strides, dilations)
    if depthwise:
        channels, mult = w.shape[2], w.shape[3]
        weight = w.permute(2, 3, 0, 1).reshape(channels * mult, 1, kh, kw)
        y = F.conv2d(xc, weight, stride=strides, dilation=dilations, groups=channels)
    else:
        y = F.conv2d(xc, w.permute(3, 2, 0, 1), stride=strides, dilation=dilations)
    return y.permute(0, 2, 3, 1)


def _fused(attr, y, args):
    for op in (base64.b64decode(s).decode() for s in attr["fused_ops"]["list"]["s"]):
        if op == "BiasAdd":
            y = y + args.pop(0)
        elif op == "Relu":
            y = F.relu(y)
        elif op == "Relu6":
            y = y.clamp(0, 6)
        else:
            raise ValueError(f"fused op {op} is not supported")
    return y


def _resize_bilinear(attr, x, size):
    """TF ResizeBilinear (NHWC) with its align_corners / half_pixel_centers conventions."""
    out_h, out_w = int(size[0]), int(size[1])
    in_h, in_w = x.shape[1], x.shape[2]
    align = attr.get("align_corners", {}).get("b", False)
    half = attr.get("half_pixel_centers", {}).get("b", False)

    def source(out, inp):
        scale = (inp - 1) / (out - 1) if align and out > 1 else inp / out
        pos = torch.arange(out, dtype=torch.float32)
        pos = (pos + 0.5) * scale - 0.5 if half else pos * scale
        pos = pos.clamp(min=0)
        low = pos.floor().long().clamp(max=inp - 1)
        high = (low + 1).clamp(max=inp - 1)
        return low, high, pos - low.float()

    y0, y1, fy = source(out_h, in_h)
    x0, x1, fx = source(out_w, in_w)
    top = x[:, y0] * (1 - fy)[None, :, None, None] + x[:, y1] * fy[None, :, None, None]
    return top[:, :, x0] * (1 - fx)[None, None, :, None] + top[:, :, x1] * fx[None, None, :, None]


def _strided_slice(attr, x, begin, end, stride):
    masks = {k: int(attr.get(k, {}).get("i", 0)) for k in
             ("begin_mask", "end_mask", "shrink_axis_mask", "ellipsis_mask", "new_axis_mask")}
    if masks["ellipsis_mask"] or masks["new_axis_mask"]:
        raise ValueError("StridedSlice with ellipsis or new axes is not supported")
    index = []
    for axis, (b, e, s) in enumerate(zip(begin.tolist(), end.tolist(), stride.tolist())):
        if masks["shrink_axis_mask"] >> axis & 1:
            index.append(b)
            continue
        index.append(slice(None if masks["begin_mask"] >> axis & 1 else b,
                           None if masks["end_mask"] >> axis & 1 else e, s))
    return x[tuple(index)]


def _max_pool(attr, x):
    kernel, strides = _ints(attr, "ksize")[1:3], _ints(attr, "strides")[1:3]
    xc = x.permute(0, 3, 1, 2)
    if _string(attr, "padding") == "SAME":
        xc = _pad_same(xc, kernel, strides, (1, 1), value=-math.inf)
    return F.max_pool2d(xc, kernel, strides).permute(0, 2, 3, 1)


def _pad(x, paddings, value=0.0):
    """TF Pad / PadV2: paddings is [rank, 2] (before, after) per axis, first axis first."""
    flat = []
    for before, after in reversed(paddings.tolist()):
        flat += [int(before), int(after)]
    return F.pad(x, flat, value=float(value))


def _sparse_to_dense(indices, shape, values, default):
    """TF SparseToDense: a tensor of `shape` holding `default`, `values` at `indices`."""
    size = [int(v) for v in shape.reshape(-1).tolist()]
    out = torch.full(size, default.item(), dtype=values.dtype)
    index = indices.long() if indices.dim() == 2 else indices.long().reshape(-1, 1)
    if index.shape[0]:
        out[tuple(index.t())] = values.reshape(-1).expand(index.shape[0])
    return out


def _split_v(attr, x, sizes, axis):
    sizes = [int(v) for v in sizes.tolist()]
    if -1 in sizes:
        sizes[sizes.index(-1)] = x.shape[int(axis)] - (sum(sizes) + 1)
    return list(torch.split(x, sizes, dim=int(axis)))


def _run_op(node, ins):
    op, attr = node["op"], node.get("attr", {})
    simple = {
        "Identity": lambda: ins[0], "Relu": lambda: F.relu(ins[0]),
        "Relu6": lambda: ins[0].clamp(0, 6), "Sigmoid": lambda: torch.sigmoid(ins[0]),
        "LeakyRelu": lambda: F.leaky_relu(ins[0], attr.get("alpha", {}).get("f", 0.2)),
        "Transpose": lambda: ins[0].permute([int(v) for v in ins[1].tolist()]),
        "Pad": lambda: _pad(ins[0], ins[1]), "PadV2": lambda: _pad(ins[0], ins[1], ins[2].item()),
        "SparseToDense": lambda: _sparse_to_dense(*ins),
        "Add": lambda: ins[0] + ins[1], "AddV2": lambda: ins[0] + ins[1],
        "Sub": lambda: ins[0] - ins[1], "Mul": lambda: ins[0] * ins[1],
        "FloorDiv": lambda: torch.div(ins[0], ins[1], rounding_mode="floor"),
        "FloorMod": lambda: torch.remainder(ins[0], ins[1]),
        "Equal": lambda: ins[0] == ins[1],
        "Reshape": lambda: ins[0].reshape([int(v) for v in ins[1].tolist()]),
        "ExpandDims": lambda: ins[0].unsqueeze(int(ins[1])),
        "Mean": lambda: ins[0].mean(dim=[int(v) for v in ins[1].reshape(-1).tolist()],
                                    keepdim=attr.get("keep_dims", {}).get("b", False)),
        "ConcatV2": lambda: torch.cat(ins[:-1], dim=int(ins[-1])),
        "GatherV2": lambda: torch.index_select(ins[0], int(ins[2]), ins[1].reshape(-1).long())
        .reshape(list(ins[0].shape[:int(ins[2])]) + list(ins[1].shape) +
                 list(ins[0].shape[int(ins[2]) + 1:])),
    }
    if op in simple:
        return [simple[op]()]
    if op == "Cast":
        target = attr["DstT"]["type"]
        return [ins[0].to({"DT_FLOAT": torch.float32, "DT_INT32": torch.int32}[target])]
    if op == "Conv2D":
        return [_conv(attr, ins[0], ins[1], depthwise=False)]
    if op == "DepthwiseConv2dNative":
        return [_conv(attr, ins[0], ins[1], depthwise=True)]
    if op == "_FusedConv2D":
        return [_fused(attr, _conv(attr, ins[0], ins[1], depthwise=False), list(ins[2:]))]
    if op == "FusedDepthwiseConv2dNative":
        return [_fused(attr, _conv(attr, ins[0], ins[1], depthwise=True), list(ins[2:]))]
    if op == "ResizeBilinear":
        return [_resize_bilinear(attr, ins[0], ins[1].tolist())]
    if op == "MaxPool":
        return [_max_pool(attr, ins[0])]
    if op == "StridedSlice":
        return [_strided_slice(attr, *ins)]
    if op == "SplitV":
        return _split_v(attr, *ins)
    if op == "TopKV2":
        values, indices = torch.topk(ins[0], int(ins[1]), sorted=True)
        return [values, indices.to(torch.int32)]
    raise ValueError(f"operation {op} (node {node['name']}) is not supported")


class GraphModel:
    """model.json of a TF.js graph model and its weight shards, executed node by node."""

    def __init__(self, model_json):
        with open(model_json) as f:
            model = json.load(f)
        if model.get("format") != "graph-model":
            raise ValueError(f"{model_json}: not a TF.js graph model")
        self.weights = _read_weights(os.path.dirname(model_json), model["weightsManifest"])
        self.nodes = {n["name"]: n for n in model["modelTopology"]["node"]}

    def run(self, feeds, outputs):
        values = {name: [t] for name, t in feeds.items()}
        values.update({name: [t] for name, t in self.weights.items()})
        with torch.no_grad():
            for name in self._order([o.partition(":")[0] for o in outputs], values):
                node = self.nodes[name]
                ins = [self._value(values, i) for i in self._inputs(node)]
                values[name] = _run_op(node, ins)
            return [self._value(values, o) for o in outputs]

    @staticmethod
    def _inputs(node):
        return [i for i in node.get("input", []) if not i.startswith("^")]

    @staticmethod
    def _value(values, ref):
        name, _, index = ref.partition(":")
        return values[name][int(index or 0)]

    def _order(self, wanted, known):
        """The nodes to run for `wanted`, each after its inputs (iterative depth-first)."""
        order, done, stack = [], set(known), [(n, False) for n in wanted]
        while stack:
            name, expanded = stack.pop()
            if name in done:
                continue
            if expanded:
                done.add(name)
                order.append(name)
                continue
            if name not in self.nodes or self.nodes[name]["op"] == "Const":
                raise ValueError(f"node {name} has no value (no weights, not fed)")
            stack.append((name, True))
            stack.extend((i.partition(":")[0], False) for i in self._inputs(self.nodes[name]))
        return order
