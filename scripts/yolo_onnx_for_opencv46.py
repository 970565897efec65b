#!/usr/bin/python3
"""Rewrite a stock Ultralytics YOLOv8-seg ONNX export so that OpenCV 4.6 loads and runs it.

Usage: /usr/bin/python3 scripts/yolo_onnx_for_opencv46.py IN.onnx OUT.onnx

Why: OpenCV 4.6 (Debian 12's python3-opencv / libopencv-dev) trips on two forms that
newer exports use, and gives no useful error for either:

  * Split with its sizes as a second input (opset 13 and later): 4.6 ignores that input
    and splits into equal parts, so the outputs have the wrong shapes. The sizes are moved
    into the opset-12 `split` attribute (they must be a constant; anything else is refused).
  * Mul/Div/Add/Sub of a tensor by a constant that only broadcasts to it, such as the
    detection head's final (1, 4, A) * (1, A) strides: 4.6 fails at run time. Such a
    constant is written out in the other operand's full shape (known from ONNX shape
    inference). One-element constants are left alone: 4.6 takes them as scalars.

Then the default-domain opset import is set to 12 when every remaining node means the same
there (checked with onnx.checker); otherwise it is left and the reason printed. OpenCV 4.6
reads each node by its form, not by that number. The input must have a fixed size
(OpenCV 4.6 cannot run a dynamic one); the model's WxH is printed at the end, to be passed
as `--input WxH` or `input_width`/`input_height`. OUT is written to OUT.part and renamed, so
a failure leaves no partial file and never replaces an existing OUT.
"""

import argparse
import copy
import os
import sys

import numpy as np
import onnx
from onnx import checker, helper, numpy_helper, shape_inference

TARGET_OPSET = 12
ELEMENTWISE_OPS = ("Mul", "Div", "Add", "Sub")
SOFTMAX_OPS = ("Softmax", "LogSoftmax", "Hardmax")
# String attribute values that opset 11's Resize and Pad know (later opsets added more).
OPSET12_STRINGS = {
    ("Resize", "coordinate_transformation_mode"): {
        "half_pixel", "pytorch_half_pixel", "align_corners", "asymmetric",
        "tf_half_pixel_for_nn", "tf_crop_and_resize"},
    ("Resize", "mode"): {"nearest", "linear", "cubic"},
    ("Resize", "nearest_mode"): {"round_prefer_floor", "round_prefer_ceil", "floor", "ceil"},
    ("Pad", "mode"): {"constant", "reflect", "edge"},
}


def warn(message):
    """Print a warning that does not stop the conversion."""
    print(f"warning: {message}", file=sys.stderr)


class ConversionError(Exception):
    """A model (or a path) that this script refuses, with the reason."""


def load_model(path):
    """The model at `path`, refused when missing or not ONNX."""
    if not os.path.exists(path):
        raise ConversionError(f"{path}: no such file")
    if not os.path.isfile(path):
        raise ConversionError(f"{path}: not a file")
    try:
        model = onnx.load(path)
    except Exception as error:  # protobuf's DecodeError, or external data that is missing
        raise ConversionError(f"{path}: not an ONNX model ({error})") from error
    if model.ir_version <= 0 or not model.opset_import or not model.graph.node:
        raise ConversionError(f"{path}: not an ONNX model (no IR version, opset or nodes)")
    return model


def default_opset(model):
    """The version of the default ("" / "ai.onnx") domain the model imports."""
    for entry in model.opset_import:
        if entry.domain in ("", "ai.onnx"):
            return entry.version
    raise ConversionError("the model imports no default-domain (ai.onnx) opset")


def input_size(model, path):
    """(width, height) of the model's single NCHW input; refused when not fixed."""
    constants = {init.name for init in model.graph.initializer}
    inputs = [value for value in model.graph.input if value.name not in constants]
    if len(inputs) != 1:
        raise ConversionError(f"{path}: expected one image input, found {len(inputs)}")
    dims = inputs[0].type.tensor_type.shape.dim
    shape = [dim.dim_value if dim.HasField("dim_value") else (dim.dim_param or "?") for dim in dims]
    if len(shape) != 4:
        raise ConversionError(f"{path}: input '{inputs[0].name}' has shape {shape}, not N×C×H×W")
    if not all(isinstance(size, int) and size > 0 for size in shape):
        raise ConversionError(
            f"{path}: input '{inputs[0].name}' has a dynamic size {shape} (N, C, H, W); "
            "OpenCV 4.6 needs a fixed one: export again with dynamic=False and imgsz=H,W")
    return shape[3], shape[2]


def constant_node_value(node):
    """The value of a Constant node as a numpy array, or None for an unusual form."""
    dtypes = {"value_int": np.int64, "value_ints": np.int64,
              "value_float": np.float32, "value_floats": np.float32}
    for attribute in node.attribute:
        if attribute.name == "value":
            return numpy_helper.to_array(attribute.t)
        if attribute.name in dtypes:
            return np.array(helper.get_attribute_value(attribute), dtypes[attribute.name])
    return None


def constant_values(graph):
    """Name -> numpy array of every initializer and Constant node output of the graph."""
    values = {init.name: numpy_helper.to_array(init) for init in graph.initializer}
    for node in graph.node:
        if node.op_type == "Constant" and node.domain in ("", "ai.onnx"):
            value = constant_node_value(node)
            if value is not None:
                values[node.output[0]] = value
    return values


def known_shapes(model):
    """Name -> shape tuple of every value whose shape ONNX shape inference fixes fully."""
    try:
        inferred = shape_inference.infer_shapes(model).graph
    except Exception as error:  # inference is only a help: carry on with the graph's own
        warn(f"shape inference failed ({error}); using the shapes in the file")
        inferred = model.graph
    shapes = {}
    for value in list(inferred.input) + list(inferred.value_info) + list(inferred.output):
        dims = value.type.tensor_type.shape.dim
        if value.type.tensor_type.HasField("shape") and all(d.HasField("dim_value") for d in dims):
            shapes[value.name] = tuple(d.dim_value for d in dims)
    return shapes


def split_sizes_to_attribute(graph, constants):
    """Move constant Split sizes from the second input into the `split` attribute.

    Returns the names of the size constants no longer used by those Split nodes."""
    moved = []
    for node in graph.node:
        if node.op_type != "Split" or len(node.input) < 2 or not node.input[1]:
            continue
        sizes_name = node.input[1]
        if sizes_name not in constants:
            raise ConversionError(
                f"Split node '{node.name}' takes its sizes from '{sizes_name}', which is not a "
                "constant (initializer or Constant node); cannot write them as the opset-12 "
                "`split` attribute. Export with simplify=True (constant folding) and try again")
        sizes = [int(size) for size in np.asarray(constants[sizes_name]).reshape(-1)]
        del node.input[1:]
        node.attribute.append(helper.make_attribute("split", sizes))
        moved.append(sizes_name)
    return moved


def unique_name(graph, wanted):
    """`wanted`, or `wanted_N`, whichever names no value of the graph yet."""
    taken = {init.name for init in graph.initializer}
    taken.update(value.name for value in graph.input)
    for node in graph.node:
        taken.update(node.output)
    name, number = wanted, 1
    while name in taken:
        name, number = f"{wanted}_{number}", number + 1
    return name


def full_shape_for(node, index, constants, shapes):
    """The shape to write input `index` of an elementwise node in, or None to leave it."""
    value = constants.get(node.input[index])
    other = node.input[1 - index]
    if value is None or other in constants or value.size <= 1:
        return None
    other_shape = shapes.get(other)
    if other_shape is None:
        warn(f"{node.op_type} '{node.name}': shape of '{other}' unknown; "
              f"constant '{node.input[index]}' {value.shape} left as it is")
        return None
    if value.shape == other_shape:
        return None
    try:
        broadcast = np.broadcast_shapes(value.shape, other_shape)
    except ValueError:
        broadcast = None
    if broadcast != other_shape:
        warn(f"{node.op_type} '{node.name}': constant '{node.input[index]}' "
              f"{value.shape} does not broadcast into {other_shape}; left as it is")
        return None
    return other_shape


def materialise_broadcast_constants(graph, constants, shapes):
    """Write the constants of Mul/Div/Add/Sub nodes in the other operand's full shape.

    Returns (the names of the new full constants, the names of the replaced ones)."""
    made, replaced, cache = [], [], {}
    for node in graph.node:
        if node.op_type not in ELEMENTWISE_OPS or len(node.input) != 2:
            continue
        for index in (0, 1):
            shape = full_shape_for(node, index, constants, shapes)
            if shape is None:
                continue
            source = node.input[index]
            if (source, shape) not in cache:
                name = unique_name(graph, f"{source}_full")
                full = np.ascontiguousarray(np.broadcast_to(constants[source], shape))
                graph.initializer.append(numpy_helper.from_array(full, name))
                cache[(source, shape)] = name
                made.append(f"{source} {constants[source].shape} -> {name} {shape}")
            node.input[index] = cache[(source, shape)]
            replaced.append(source)
            if node.op_type == "Div" and index == 0:
                warn(f"Div '{node.name}' divides a constant by a tensor: OpenCV 4.6 computes "
                     "tensor / constant instead unless the constant is a single number")
    return made, replaced


def remove_unused_constants(graph, names):
    """Drop the initializers and Constant nodes among `names` that nothing reads any more."""
    used = {name for node in graph.node for name in node.input}
    used.update(value.name for value in graph.output)
    unused = set(names) - used
    kept = [init for init in graph.initializer if init.name not in unused]
    del graph.initializer[:]
    graph.initializer.extend(kept)
    kept_inputs = [value for value in graph.input if value.name not in unused]
    del graph.input[:]
    graph.input.extend(kept_inputs)
    kept_nodes = [node for node in graph.node
                  if not (node.op_type == "Constant" and node.output[0] in unused)]
    del graph.node[:]
    graph.node.extend(kept_nodes)


def softmax_blocker(node, shapes, opset):
    """Why a Softmax-like node means something else at opset 12, or None (then it is made so).

    Before opset 13 these ops flatten the input into 2-D at `axis`; from 13 on they work
    along `axis` alone. Both agree only when `axis` is the last dimension."""
    shape = shapes.get(node.input[0])
    if shape is None:
        return f"{node.op_type} '{node.name}': input rank unknown"
    attributes = {a.name: helper.get_attribute_value(a) for a in node.attribute}
    axis = attributes.get("axis", -1 if opset >= 13 else 1)
    if axis % len(shape) != len(shape) - 1:
        return (f"{node.op_type} '{node.name}' over axis {axis} of a rank-{len(shape)} input "
                "(before opset 13 it would run over all dimensions from that axis on)")
    set_attribute(node, "axis", len(shape) - 1)
    return None


def set_attribute(node, name, value):
    """Give `node` the attribute `name` = `value`, replacing any it had."""
    remove_attribute(node, name)
    node.attribute.append(helper.make_attribute(name, value))


def remove_attribute(node, name):
    """Remove the attribute `name` from `node` if it has it."""
    kept = [a for a in node.attribute if a.name != name]
    del node.attribute[:]
    node.attribute.extend(kept)


def string_blocker(node):
    """Why a node's string attribute has a value opset 12 lacks, or None."""
    for attribute in node.attribute:
        allowed = OPSET12_STRINGS.get((node.op_type, attribute.name))
        if allowed is None:
            continue
        value = helper.get_attribute_value(attribute).decode()
        if value not in allowed:
            return (f"{node.op_type} '{node.name}': {attribute.name} '{value}' "
                    "is newer than opset 12")
    return None


def opset12_form(graph, node, shapes, opset, empty_roi):
    """Rewrite `node` into its opset-12 spelling where that means the same; why not, or None."""
    if node.op_type in SOFTMAX_OPS:
        return softmax_blocker(node, shapes, opset)
    if node.op_type == "Reshape":
        attributes = {a.name: helper.get_attribute_value(a) for a in node.attribute}
        if attributes.get("allowzero", 0) != 0:
            return f"Reshape '{node.name}' with allowzero=1 (opset 14)"
        remove_attribute(node, "allowzero")  # 0 is the only behaviour opset 12 has
    if node.op_type == "Resize" and len(node.input) > 1 and not node.input[1]:
        if not empty_roi:  # opset 11's Resize wants a roi input, empty when unused
            empty_roi.append(unique_name(graph, "resize_empty_roi"))
            graph.initializer.append(numpy_helper.from_array(np.zeros(0, np.float32), empty_roi[0]))
        node.input[1] = empty_roi[0]
    return string_blocker(node)


def as_opset12(model, shapes):
    """(a copy of `model` at opset 12, []) when it means the same there, else (None, reasons)."""
    opset = default_opset(model)
    candidate = copy.deepcopy(model)
    empty_roi = []
    reasons = []
    for node in candidate.graph.node:
        if node.domain in ("", "ai.onnx"):
            reason = opset12_form(candidate.graph, node, shapes, opset, empty_roi)
            if reason:
                reasons.append(reason)
    if reasons:
        return None, reasons
    for entry in candidate.opset_import:
        if entry.domain in ("", "ai.onnx"):
            entry.version = TARGET_OPSET
    try:
        checker.check_model(candidate, full_check=True)
    except Exception as error:
        return None, [f"onnx.checker at opset 12: {str(error).strip().splitlines()[0]}"]
    return candidate, []


def relabel_opset(model, shapes):
    """(the model at opset 12 where it means the same there, else as it was; lines to print)."""
    opset = default_opset(model)
    if opset <= TARGET_OPSET:
        return model, [f"opset import: {opset} (unchanged)"]
    downgraded, reasons = as_opset12(model, shapes)
    if downgraded is not None:
        return downgraded, [f"opset import: {opset} -> {TARGET_OPSET}"]
    lines = [f"opset import left at {opset}; set to 12 it would not be the same model:"]
    lines += [f"  {reason}" for reason in reasons]
    lines.append("  OpenCV 4.6 reads each node by its form, whatever the opset number says")
    if any(node.op_type == "Split" and any(a.name == "split" for a in node.attribute)
           for node in model.graph.node):
        lines.append(f"  other runtimes may refuse the file: a Split `split` attribute is not "
                     f"opset-{opset} ONNX")
    return model, lines


def check_paths(in_path, out_path):
    """Refuse an output path that is the input, or a folder."""
    same = os.path.realpath(in_path) == os.path.realpath(out_path)
    if not same and os.path.exists(out_path) and os.path.exists(in_path):
        same = os.path.samefile(in_path, out_path)
    if same:
        raise ConversionError(f"{out_path}: the output is the input file {in_path}; "
                              "give another output path")
    if os.path.isdir(out_path):
        raise ConversionError(f"{out_path}: is a folder; give the output file's path")


def write_atomically(model, out_path):
    """Write `model` to OUT.part, then rename it to OUT; on failure remove OUT.part."""
    part = out_path + ".part"
    try:
        data = model.SerializeToString()
        with open(part, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(part, out_path)
    except BaseException as error:
        if os.path.exists(part):
            os.remove(part)
        if isinstance(error, (OSError, ValueError)):
            raise ConversionError(f"{out_path}: cannot write ({error})") from error
        raise


def convert(in_path, out_path):
    """Convert IN to OUT; returns the lines to print (the last one gives the input size)."""
    if not os.path.exists(in_path):
        raise ConversionError(f"{in_path}: no such file")
    check_paths(in_path, out_path)
    model = load_model(in_path)
    width, height = input_size(model, in_path)
    shapes = known_shapes(model)  # on the file as it came, while it is still valid ONNX
    constants = constant_values(model.graph)
    try:
        moved = split_sizes_to_attribute(model.graph, constants)
    except ConversionError as error:
        raise ConversionError(f"{in_path}: {error}") from error
    made, replaced = materialise_broadcast_constants(model.graph, constants, shapes)
    remove_unused_constants(model.graph, moved + replaced)
    lines = [f"Split nodes given the opset-12 `split` attribute: {len(moved)}",
             f"constants written in full shape: {len(made)}"] + [f"  {line}" for line in made]
    model, opset_lines = relabel_opset(model, shapes)
    lines += opset_lines
    write_atomically(model, out_path)
    lines.append(f"wrote {out_path}")
    lines.append(f"model input: {width}x{height} (pass --input {width}x{height}, or "
                 f"input_width: {width}, input_height: {height})")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Make a fixed-size Ultralytics YOLOv8-seg ONNX export run in OpenCV 4.6.")
    parser.add_argument("input", help="the stock export (.onnx)")
    parser.add_argument("output", help="where to write the converted model (.onnx)")
    args = parser.parse_args(argv)
    try:
        lines = convert(args.input, args.output)
    except ConversionError as error:
        print(f"{parser.prog}: error: {error}", file=sys.stderr)
        return 1
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
