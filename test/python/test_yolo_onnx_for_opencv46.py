"""Tests of scripts/yolo_onnx_for_opencv46.py with Debian 12's OpenCV 4.6 and python3-onnx.

Small graphs built with onnx.helper hold each pattern OpenCV 4.6 trips on; the converted
graphs must load and run in cv2.dnn and match numpy, the unconverted ones are shown to fail.
The shared YOLOv8n-seg exports (../shared or $PLY_SLAM_SHARED; missing: skipped, or failed
under CI=true) must give the same outputs after conversion, and so must a stock-form copy of
them (Split sizes as an input, (1, A) strides), which OpenCV 4.6 cannot run.

Run: /usr/bin/python3 -m unittest discover -s test/python -p 'test_yolo_onnx_for_opencv46.py' -v
"""

import contextlib
import importlib.util
import io
import os
import pathlib
import subprocess
import sys
import tempfile
import unittest
from unittest import mock

os.environ.setdefault("OPENCV_LOG_LEVEL", "ERROR")  # before cv2 loads: no import warnings

import cv2  # noqa: E402
import numpy as np  # noqa: E402
import onnx  # noqa: E402
from onnx import TensorProto, checker, helper, numpy_helper  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "yolo_onnx_for_opencv46.py"
IMAGE = "data/tum/rgbd_dataset_freiburg1_xyz_37/rgb/1305031102.175304.png"
FLOAT = TensorProto.FLOAT


def load_script():
    spec = importlib.util.spec_from_file_location("yolo_onnx_for_opencv46", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


converter = load_script()


def shared_dir():
    """$PLY_SLAM_SHARED, else the first `shared` folder beside the repository or above it."""
    if os.environ.get("PLY_SLAM_SHARED"):
        return pathlib.Path(os.environ["PLY_SLAM_SHARED"])
    for folder in REPO.parents:
        if (folder / "shared").is_dir():
            return folder / "shared"
    return REPO.parent / "shared"


def require_shared(test, relative):
    """The shared file's path; the test skips when it is missing, or fails under CI=true."""
    path = shared_dir() / relative
    if not path.exists():
        message = f"shared data missing: {path} (set PLY_SLAM_SHARED to the folder with models/)"
        if os.environ.get("CI") == "true":
            test.fail(f"CI=true but {message}")
        test.skipTest(message)
    return path


def make_model(nodes, inputs, outputs, initializers=(), opset=17):
    graph = helper.make_graph(nodes, "g", inputs, outputs, list(initializers))
    return helper.make_model(graph, opset_imports=[helper.make_opsetid("", opset)])


def tensor(name, shape, elem_type=FLOAT):
    return helper.make_tensor_value_info(name, elem_type, shape)


def split_model(sizes_from="initializer"):
    """x (1, 8, 5, 3) split 2 + 6 along axis 1, each part through Relu (opset 17 form)."""
    sizes = np.array([2, 6], np.int64)
    nodes, initializers = [], []
    if sizes_from == "initializer":
        initializers.append(numpy_helper.from_array(sizes, "sizes"))
    elif sizes_from == "constant":
        nodes.append(helper.make_node("Constant", [], ["sizes"],
                                      value=numpy_helper.from_array(sizes)))
    else:  # computed: a Cast of a constant is not itself a constant
        initializers.append(numpy_helper.from_array(sizes.astype(np.int32), "sizes32"))
        nodes.append(helper.make_node("Cast", ["sizes32"], ["sizes"], to=TensorProto.INT64))
    nodes += [helper.make_node("Split", ["x", "sizes"], ["a", "b"], axis=1, name="split"),
              helper.make_node("Relu", ["a"], ["ra"]), helper.make_node("Relu", ["b"], ["rb"])]
    return make_model(nodes, [tensor("x", [1, 8, 5, 3])],
                      [tensor("ra", [1, 2, 5, 3]), tensor("rb", [1, 6, 5, 3])], initializers)


ANCHORS = 7
NUMPY_OPS = {"Mul": np.multiply, "Div": np.divide, "Add": np.add, "Sub": np.subtract}


def strides_model(op, constant, as_constant_node=False):
    """x (1, 4, 1, A) reshaped to (1, 4, A), then `op` with `constant`, as the detection head."""
    nodes = [helper.make_node("Reshape", ["x", "shape"], ["boxes"])]
    initializers = [numpy_helper.from_array(np.array([1, 4, ANCHORS], np.int64), "shape")]
    if as_constant_node:
        nodes.append(helper.make_node("Constant", [], ["strides"],
                                      value=numpy_helper.from_array(constant)))
    else:
        initializers.append(numpy_helper.from_array(constant, "strides"))
    nodes.append(helper.make_node(op, ["boxes", "strides"], ["y"], name="head"))
    return make_model(nodes, [tensor("x", [1, 4, 1, ANCHORS])], [tensor("y", [1, 4, ANCHORS])],
                      initializers)


def strides():
    return (np.arange(ANCHORS, dtype=np.float32).reshape(1, ANCHORS) % 3 + 1) * 8


def run_opencv(path, blob, outputs):
    net = cv2.dnn.readNetFromONNX(str(path))
    net.setInput(blob)
    return net.forward(outputs)


def node_named(model, name):
    return next(node for node in model.graph.node if node.name == name)


def initializer_array(model, name):
    found = [init for init in model.graph.initializer if init.name == name]
    return numpy_helper.to_array(found[0]) if found else None


def opset_of(model):
    return next(entry.version for entry in model.opset_import if entry.domain in ("", "ai.onnx"))


class ConverterTestCase(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = pathlib.Path(self._tmp.name)
        self.rng = np.random.default_rng(51)

    def tearDown(self):
        self._tmp.cleanup()

    def save(self, model, name="in.onnx"):
        path = self.tmp / name
        onnx.save(model, str(path))
        return path

    def convert(self, model):
        """(the converted model, the lines the converter printed)."""
        source, target = self.save(model), self.tmp / "out.onnx"
        lines = converter.convert(str(source), str(target))
        return onnx.load(str(target)), lines

    def run_cli(self, *args):
        return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)],
                              capture_output=True, text=True, timeout=60)


class SplitSizes(ConverterTestCase):
    def test_constant_sizes_become_the_opset12_split_attribute(self):
        for sizes_from in ("initializer", "constant"):
            with self.subTest(sizes_from=sizes_from):
                converted, _ = self.convert(split_model(sizes_from))
                split = node_named(converted, "split")
                self.assertEqual(list(split.input), ["x"])
                attributes = {a.name: helper.get_attribute_value(a) for a in split.attribute}
                self.assertEqual(attributes["split"], [2, 6])
                self.assertEqual(attributes["axis"], 1)
                self.assertIsNone(initializer_array(converted, "sizes"))
                self.assertNotIn("Constant", [node.op_type for node in converted.graph.node])
                self.assertEqual(opset_of(converted), 12)
                checker.check_model(converted, full_check=True)

    def test_opencv_runs_the_converted_split_like_numpy(self):
        converted, _ = self.convert(split_model())
        path = self.save(converted, "converted.onnx")
        x = self.rng.standard_normal((1, 8, 5, 3)).astype(np.float32)
        a, b = run_opencv(path, x, ["ra", "rb"])
        np.testing.assert_array_equal(a, np.maximum(x[:, :2], 0))
        np.testing.assert_array_equal(b, np.maximum(x[:, 2:], 0))

    def test_opencv_ignores_the_sizes_input_of_the_unconverted_split(self):
        path = self.save(split_model())
        x = self.rng.standard_normal((1, 8, 5, 3)).astype(np.float32)
        a, b = run_opencv(path, x, ["ra", "rb"])
        self.assertEqual((a.shape, b.shape), ((1, 4, 5, 3), (1, 4, 5, 3)))  # not 2 + 6

    def test_sizes_that_are_not_constant_are_refused(self):
        source, target = self.save(split_model("computed")), self.tmp / "out.onnx"
        result = self.run_cli(source, target)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(str(source), result.stderr)
        self.assertIn("Split node 'split'", result.stderr)
        self.assertIn("not a constant", result.stderr)
        self.assertEqual(os.listdir(self.tmp), ["in.onnx"])


class BroadcastConstants(ConverterTestCase):
    def test_the_strides_constant_is_written_in_the_full_shape(self):
        for as_constant_node in (False, True):
            with self.subTest(as_constant_node=as_constant_node):
                converted, lines = self.convert(strides_model("Mul", strides(), as_constant_node))
                name = node_named(converted, "head").input[1]
                full = initializer_array(converted, name)
                self.assertEqual(full.shape, (1, 4, ANCHORS))
                np.testing.assert_array_equal(full, np.broadcast_to(strides(), (1, 4, ANCHORS)))
                self.assertIsNone(initializer_array(converted, "strides"))
                self.assertNotIn("Constant", [node.op_type for node in converted.graph.node])
                self.assertIn("constants written in full shape: 1", lines)
                self.assertEqual(opset_of(converted), 12)

    def test_opencv_runs_the_converted_ops_like_numpy_and_fails_on_the_stock_ones(self):
        x = self.rng.uniform(0.5, 2, (1, 4, 1, ANCHORS)).astype(np.float32)
        for op, numpy_op in NUMPY_OPS.items():
            with self.subTest(op=op):
                stock = strides_model(op, strides())
                with self.assertRaises(cv2.error):
                    run_opencv(self.save(stock, "stock.onnx"), x, ["y"])
                converted, _ = self.convert(stock)
                (y,) = run_opencv(self.save(converted, "converted.onnx"), x, ["y"])
                expected = numpy_op(x.reshape(1, 4, ANCHORS), strides())
                np.testing.assert_allclose(y, expected, rtol=1e-6)

    def test_a_constant_divided_by_a_tensor_is_warned_about(self):
        model = strides_model("Div", strides())
        head = node_named(model, "head")
        head.input[0], head.input[1] = head.input[1], head.input[0]
        warnings = io.StringIO()
        with contextlib.redirect_stderr(warnings):
            converted, _ = self.convert(model)
        self.assertIn("Div 'head' divides a constant by a tensor", warnings.getvalue())
        x = self.rng.uniform(0.5, 2, (1, 4, 1, ANCHORS)).astype(np.float32)
        (y,) = run_opencv(self.save(converted, "converted.onnx"), x, ["y"])
        boxes = x.reshape(1, 4, ANCHORS)
        np.testing.assert_allclose(y, boxes / strides(), rtol=1e-6)  # not strides / boxes

    def test_single_number_constants_are_left_alone(self):
        for constant in (np.array(8, np.float32), np.array([8], np.float32)):
            with self.subTest(shape=constant.shape):
                converted, lines = self.convert(strides_model("Mul", constant))
                self.assertEqual(node_named(converted, "head").input[1], "strides")
                self.assertIn("constants written in full shape: 0", lines)


class OpsetImport(ConverterTestCase):
    def head_model(self, softmax_axis):
        """Reshape (allowzero=0) and Resize with no roi (opset 13+ forms), then Softmax."""
        nodes = [
            helper.make_node("Reshape", ["x", "shape"], ["r"], allowzero=0),
            helper.make_node("Resize", ["r", "", "scales"], ["up"], mode="nearest",
                             coordinate_transformation_mode="asymmetric", nearest_mode="floor"),
            helper.make_node("Softmax", ["up"], ["y"], axis=softmax_axis, name="softmax"),
        ]
        initializers = [numpy_helper.from_array(np.array([1, 3, 4, 5], np.int64), "shape"),
                        numpy_helper.from_array(np.array([1, 1, 2, 2], np.float32), "scales")]
        return make_model(nodes, [tensor("x", [1, 3, 20, 1])], [tensor("y", [1, 3, 8, 10])],
                          initializers)

    def test_opset_12_when_the_nodes_mean_the_same_there(self):
        converted, lines = self.convert(self.head_model(softmax_axis=-1))
        self.assertEqual(opset_of(converted), 12)
        self.assertIn("opset import: 17 -> 12", lines)
        checker.check_model(converted, full_check=True)
        x = self.rng.standard_normal((1, 3, 20, 1)).astype(np.float32)
        (y,) = run_opencv(self.save(converted, "converted.onnx"), x, ["y"])
        up = x.reshape(1, 3, 4, 5).repeat(2, axis=2).repeat(2, axis=3)
        expected = np.exp(up) / np.exp(up).sum(axis=3, keepdims=True)
        np.testing.assert_allclose(y, expected, rtol=1e-5, atol=1e-7)

    def test_softmax_over_an_inner_axis_keeps_the_opset_and_says_why(self):
        model = self.head_model(softmax_axis=1)
        converted, lines = self.convert(model)
        self.assertEqual(opset_of(converted), 17)
        text = "\n".join(lines)
        self.assertIn("opset import left at 17", text)
        self.assertIn("Softmax 'softmax' over axis 1 of a rank-4 input", text)
        self.assertEqual(converted.graph, model.graph)  # nothing else was touched

    def test_string_attributes_newer_than_opset_12_keep_the_opset(self):
        newer = helper.make_node("Resize", ["x", "", "scales"], ["y"], name="up",
                                 coordinate_transformation_mode="half_pixel_symmetric")
        self.assertIn("half_pixel_symmetric", converter.string_blocker(newer))
        known = helper.make_node("Pad", ["x", "pads"], ["y"], mode="reflect")
        self.assertIsNone(converter.string_blocker(known))

    def test_opencv_46_reads_softmax_by_its_axis_whatever_the_opset(self):
        x = self.rng.standard_normal((1, 3, 4, 5)).astype(np.float32)
        expected = np.exp(x) / np.exp(x).sum(axis=1, keepdims=True)
        for opset in (12, 17):
            model = make_model([helper.make_node("Softmax", ["x"], ["y"], axis=1)],
                               [tensor("x", [1, 3, 4, 5])], [tensor("y", [1, 3, 4, 5])],
                               opset=opset)
            (y,) = run_opencv(self.save(model, f"softmax{opset}.onnx"), x, ["y"])
            np.testing.assert_allclose(y, expected, rtol=1e-5, atol=1e-7)


class Refusals(ConverterTestCase):
    def assert_refused(self, source, target, reason):
        result = self.run_cli(source, target)
        self.assertNotEqual(result.returncode, 0, result.stdout)
        self.assertIn(str(source if reason != "the output is the input" else target),
                      result.stderr)
        self.assertIn(reason, result.stderr)
        self.assertFalse(os.path.exists(str(target) + ".part"))
        return result

    def test_a_missing_file(self):
        self.assert_refused(self.tmp / "none.onnx", self.tmp / "out.onnx", "no such file")
        self.assertEqual(os.listdir(self.tmp), [])

    def test_a_file_that_is_not_onnx(self):
        for name, content in (("text.onnx", b"not a model\n"), ("empty.onnx", b""),
                              ("png.onnx", b"\x89PNG\r\n\x1a\n" + bytes(range(256)))):
            with self.subTest(name=name):
                source = self.tmp / name
                source.write_bytes(content)
                self.assert_refused(source, self.tmp / "out.onnx", "not an ONNX model")
                self.assertFalse((self.tmp / "out.onnx").exists())

    def test_a_dynamic_input_size(self):
        model = split_model()
        dims = model.graph.input[0].type.tensor_type.shape.dim
        dims[2].dim_param, dims[3].dim_param = "height", "width"
        result = self.assert_refused(self.save(model), self.tmp / "out.onnx", "dynamic size")
        self.assertIn("dynamic=False", result.stderr)
        self.assertFalse((self.tmp / "out.onnx").exists())

    def test_the_output_path_is_the_input(self):
        source = self.save(split_model())
        before = source.read_bytes()
        for target in (source, self.tmp / "." / "in.onnx"):
            with self.subTest(target=str(target)):
                self.assert_refused(source, target, "the output is the input")
                self.assertEqual(source.read_bytes(), before)

    def test_a_failure_leaves_an_existing_output_as_it_was(self):
        target = self.tmp / "out.onnx"
        target.write_bytes(b"good data")
        self.assert_refused(self.save(split_model("computed")), target, "not a constant")
        self.assertEqual(target.read_bytes(), b"good data")
        self.assertEqual(sorted(os.listdir(self.tmp)), ["in.onnx", "out.onnx"])

    def test_a_failed_write_leaves_no_part_file_and_the_old_output(self):
        source, target = self.save(split_model()), self.tmp / "out.onnx"
        target.write_bytes(b"good data")
        with mock.patch.object(converter.os, "replace", side_effect=OSError("disk full")):
            with self.assertRaisesRegex(converter.ConversionError, "out.onnx: cannot write"):
                converter.convert(str(source), str(target))
        self.assertEqual(target.read_bytes(), b"good data")
        self.assertEqual(sorted(os.listdir(self.tmp)), ["in.onnx", "out.onnx"])

    def test_an_output_folder_that_does_not_exist(self):
        target = self.tmp / "missing" / "out.onnx"
        result = self.run_cli(self.save(split_model()), target)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(f"{target}: cannot write", result.stderr)
        self.assertEqual(os.listdir(self.tmp), ["in.onnx"])

    def test_success_prints_the_input_size_last(self):
        result = self.run_cli(self.save(split_model()), self.tmp / "out.onnx")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(result.stdout.splitlines()[-1].startswith("model input: 3x5 "))
        self.assertEqual(sorted(os.listdir(self.tmp)), ["in.onnx", "out.onnx"])


def stock_form(model):
    """The shared export as a stock opset-17 export has it: Split sizes as an input (from an
    initializer) and the strides Mul by the (1, A) constant it was widened from."""
    graph = model.graph
    for node in graph.node:
        sizes = [a for a in node.attribute if a.name == "split"]
        if node.op_type == "Split" and sizes:
            graph.initializer.append(numpy_helper.from_array(
                np.array(sizes[0].ints, np.int64), f"{node.name}/sizes"))
            node.attribute.remove(sizes[0])
            node.input.append(f"{node.name}/sizes")
    mul = next(node for node in graph.node if node.name == "/model.22/Mul_2")
    full = next(init for init in graph.initializer if init.name == mul.input[1])
    row = numpy_helper.to_array(full)[0, :1, :]
    np.testing.assert_array_equal(numpy_helper.to_array(full), np.broadcast_to(row, full.dims))
    graph.initializer.remove(full)
    graph.initializer.append(numpy_helper.from_array(row.copy(), "/model.22/strides"))
    mul.input[1] = "/model.22/strides"
    return model


class SharedExports(ConverterTestCase):
    def check_export(self, name, width, height):
        source = require_shared(self, f"models/{name}")
        image = cv2.imread(str(require_shared(self, IMAGE)))
        blob = cv2.dnn.blobFromImage(image, 1 / 255.0, (width, height), swapRB=True)
        outputs = ["output0", "output1"]
        reference = run_opencv(source, blob, outputs)

        target = self.tmp / "converted.onnx"
        lines = converter.convert(str(source), str(target))
        self.assertEqual(lines[-1].split()[2], f"{width}x{height}")
        converted = run_opencv(target, blob, outputs)

        stock = self.save(stock_form(onnx.load(str(source))), "stock.onnx")
        checker.check_model(str(stock), full_check=True)  # valid opset-17 ONNX
        with self.assertRaises(cv2.error):
            run_opencv(stock, blob, outputs)
        from_stock = run_opencv(self.save(self.convert(onnx.load(str(stock)))[0], "fixed.onnx"),
                                blob, outputs)
        for label, result in (("converted", converted), ("stock converted", from_stock)):
            differences = [float(np.abs(a - b).max()) for a, b in zip(reference, result)]
            print(f"\n  {name} {label}: max |difference| output0 {differences[0]:.3g}, "
                  f"output1 {differences[1]:.3g}", file=sys.stderr)
            for a, b in zip(reference, result):
                self.assertEqual(a.shape, b.shape)
                np.testing.assert_allclose(b, a, rtol=0, atol=1e-5)

    def test_320x320(self):
        self.check_export("yolov8n-seg-320x320.onnx", 320, 320)

    def test_480x640(self):
        self.check_export("yolov8n-seg-480x640.onnx", 640, 480)


if __name__ == "__main__":
    unittest.main()
