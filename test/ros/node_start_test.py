#!/usr/bin/python3
"""rostest: starts the nodes by hand with their parameters set here. With world_frame unlike
map_frame and world_in_map [] (mapping.launch's defaults but for the world frame) mapping_node
must run; with three numbers it must stop saying what ~world_in_map needs; either node without
a config must stop saying so, the same way. Both once died without a word: the exception's
message was logged after ROS had shut its logging down."""
import os
import shutil
import subprocess
import sys
import time
import unittest

import rospy
import rostest
import yaml

import ros_test_support as support


# The config as the launch files load it into ~config.
with open(os.path.join(support.PACKAGE_DIR, "config", "tum_fr1.yaml")) as config_file:
    CONFIG = yaml.safe_load(config_file)


class NodeStart(unittest.TestCase):
    def start(self, node, name, **params):
        for key, value in params.items():
            rospy.set_param("/node_start/%s/%s" % (name, key), value)
        process = subprocess.Popen([support.tool(node), "__name:=" + name, "__ns:=/node_start"],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.addCleanup(process.kill)  # a node that failed to stop is not left running
        return process

    def test_mapping_node_runs_without_world_in_map(self):
        node = self.start("mapping_node", "no_placement", config=CONFIG,
                          world_frame="ply_slam_world", world_in_map=[])
        time.sleep(3)
        alive = node.poll() is None
        node.terminate()
        output = node.communicate(timeout=20)[0]
        self.assertTrue(alive, "mapping_node stopped: " + output)

    def test_mapping_node_says_why_it_stops(self):
        node = self.start("mapping_node", "bad_placement", config=CONFIG,
                          world_frame="ply_slam_world", world_in_map=[1.0, 2.0, 3.0])
        output = node.communicate(timeout=30)[0]
        self.assertEqual(node.returncode, 1, output)
        self.assertIn("world_in_map needs 6 numbers", output)

    def test_tracking_node_says_why_it_stops(self):
        node = self.start("tracking_node", "no_config")
        output = node.communicate(timeout=30)[0]
        self.assertEqual(node.returncode, 1, output)
        self.assertIn("config /node_start/no_config/config: no such parameter", output)

    def test_mapping_node_without_config_stops_as_tracking_node(self):
        node = self.start("mapping_node", "no_mapping_config", world_frame="ply_slam_world")
        output = node.communicate(timeout=30)[0]
        self.assertEqual(node.returncode, 1, output)
        self.assertIn("config /node_start/no_mapping_config/config: no such parameter", output)

    def test_both_nodes_name_a_bad_parameter_alike(self):
        tracker = self.start("tracking_node", "bad_map", config=CONFIG, map="/nonexistent")
        mapper = self.start("mapping_node", "bad_period", config=CONFIG, dense_publish_period=0.0)
        tracker_output = tracker.communicate(timeout=30)[0]
        mapper_output = mapper.communicate(timeout=30)[0]
        self.assertEqual(tracker.returncode, 1, tracker_output)
        self.assertEqual(mapper.returncode, 1, mapper_output)
        self.assertIn("tracking_node: ~map has no map file /nonexistent/", tracker_output)
        self.assertIn("mapping_node: ~dense_publish_period must be > 0 s", mapper_output)

    def test_mapping_node_apart_names_a_map_file_it_cannot_load(self):
        folder = support.work_dir()
        self.addCleanup(shutil.rmtree, folder, True)
        with open(os.path.join(folder, "map.plymap"), "wb") as f:
            f.write(b"not a map at all")
        node = self.start("mapping_node", "bad_map_file", config=CONFIG, map_keyframes=True,
                          map=folder)
        output = node.communicate(timeout=30)[0]
        self.assertEqual(node.returncode, 1, output)
        self.assertIn(os.path.join(folder, "map.plymap") + ": bad magic", output)

    def test_tracking_node_refuses_a_path_period_of_zero(self):
        node = self.start("tracking_node", "bad_path_period", config=CONFIG, path_period=0.0)
        output = node.communicate(timeout=30)[0]
        self.assertEqual(node.returncode, 1, output)
        self.assertIn("tracking_node: ~path_period must be > 0 s", output)


if __name__ == "__main__":
    rospy.init_node("node_start_test")
    rostest.rosrun("ply_slam", "node_start_test", NodeStart, sys.argv)
