"""test/ros/checked_run.py: a command that fails says why (its stderr), one that works returns
its output. The rostests run their tools through it (issue #53: loop_bag_replay failed when
ply_slam_synth exited 1 and kept none of its stderr)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "ros"))
import checked_run  # noqa: E402


class CheckedRun(unittest.TestCase):
    def test_a_failure_holds_the_exit_code_and_the_stderr(self):
        with self.assertRaises(AssertionError) as raised:
            checked_run.run(["sh", "-c", "echo some output; echo why it failed >&2; exit 3"])
        message = str(raised.exception)
        self.assertIn("exited with 3", message)
        self.assertIn("why it failed", message)
        self.assertIn("some output", message)

    def test_only_the_end_of_a_long_stderr_is_kept(self):
        with self.assertRaises(AssertionError) as raised:
            checked_run.run(["sh", "-c", "head -c 100000 /dev/zero | tr '\\\\0' x >&2; "
                             "echo the last line >&2; exit 1"])
        message = str(raised.exception)
        self.assertIn("the last line", message)
        self.assertLess(len(message), 3 * checked_run.KEPT_CHARS)

    def test_a_success_returns_the_output(self):
        self.assertEqual(checked_run.run(["echo", "fine"]).stdout, "fine\n")


if __name__ == "__main__":
    unittest.main()
