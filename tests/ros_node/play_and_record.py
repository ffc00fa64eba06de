#!/usr/bin/env python3
"""The live side of the ROS1 node test (test_ros_node.cpp): plays a bag's sensor topics into a running ROS
master at their recorded pace, as drivers would publish them, and records what vilslam_ros_node publishes.

    play_and_record.py BAG OUT_DIR --topics /imu0 /cam0/image_raw ... [--node /vilslam] [--speed 1]

Waits until the node subscribes to every played topic and the recorder to every node output, plays, then
waits until the node's outputs have been quiet for --quiet seconds. Writes OUT_DIR/odometry.tum,
camera_state.tum, lidar_pose.tum and path.tum (the last Path), and OUT_DIR/counts.txt (messages per output).
Exits 1 with a message when the node never connects."""
import argparse
import os
import sys
import threading
import time

import rosbag
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry, Path
from sensor_msgs.msg import PointCloud2
from tf2_msgs.msg import TFMessage


def tum_line(stamp, pose):
    p, q = pose.position, pose.orientation
    return "%d.%09d %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n" % (stamp.secs, stamp.nsecs, p.x, p.y, p.z, q.x, q.y, q.z, q.w)


class Recorder:
    def __init__(self, node):
        self.lock = threading.Lock()
        self.lines = {"odometry": [], "camera_state": [], "lidar_pose": []}
        self.counts = {"odometry": 0, "camera_state": 0, "lidar_pose": 0, "path": 0, "sparse_map": 0, "tf": 0}
        self.sparse_map_points = 0
        self.last_path = None
        self.last_message = time.monotonic()
        self.subscribers = [
            rospy.Subscriber(node + "/odometry", Odometry, self.pose, "odometry", queue_size=100000),
            rospy.Subscriber(node + "/camera_state", Odometry, self.pose, "camera_state", queue_size=100000),
            rospy.Subscriber(node + "/lidar_pose", PoseStamped, self.pose, "lidar_pose", queue_size=100000),
            rospy.Subscriber(node + "/path", Path, self.path, queue_size=1000),
            rospy.Subscriber(node + "/sparse_map", PointCloud2, self.cloud, queue_size=1000),
            rospy.Subscriber("/tf", TFMessage, self.tf, queue_size=100000),
        ]

    def seen(self, name):
        self.counts[name] += 1
        self.last_message = time.monotonic()

    def pose(self, msg, name):
        with self.lock:
            pose = msg.pose.pose if isinstance(msg, Odometry) else msg.pose
            self.lines[name].append(tum_line(msg.header.stamp, pose))
            self.seen(name)

    def path(self, msg):
        with self.lock:
            self.last_path = msg
            self.seen("path")

    def cloud(self, msg):
        with self.lock:
            self.sparse_map_points += msg.width * msg.height
            self.seen("sparse_map")

    def tf(self, msg):
        with self.lock:
            self.seen("tf")

    def connected(self):
        return all(s.get_num_connections() > 0 for s in self.subscribers)

    def write(self, out_dir):
        with self.lock:
            os.makedirs(out_dir, exist_ok=True)
            for name, lines in self.lines.items():
                with open(os.path.join(out_dir, name + ".tum"), "w") as f:
                    f.writelines(lines)
            with open(os.path.join(out_dir, "path.tum"), "w") as f:
                for p in (self.last_path.poses if self.last_path else []):
                    f.write(tum_line(p.header.stamp, p.pose))
            with open(os.path.join(out_dir, "counts.txt"), "w") as f:
                for name, count in sorted(self.counts.items()):
                    f.write("%s %d\n" % (name, count))
                f.write("sparse_map_points %d\n" % self.sparse_map_points)


def wait_for(condition, timeout_s, what):
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline or rospy.is_shutdown():
            sys.exit("play_and_record: timed out waiting for " + what)
        time.sleep(0.05)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("bag")
    parser.add_argument("out_dir")
    parser.add_argument("--topics", nargs="+", required=True)
    parser.add_argument("--node", default="/vilslam")
    parser.add_argument("--speed", type=float, default=1.0)
    parser.add_argument("--connect-timeout", type=float, default=60.0)
    parser.add_argument("--quiet", type=float, default=3.0)
    args = parser.parse_args()

    rospy.init_node("vilslam_test_player", anonymous=True, disable_signals=True)
    bag = rosbag.Bag(args.bag)
    types = {c.topic: c for c in bag._get_connections()}
    publishers = {}
    for topic in args.topics:
        if topic not in types:
            sys.exit("play_and_record: %s has no topic %s" % (args.bag, topic))
    recorder = Recorder(args.node)
    messages = list(bag.read_messages(topics=args.topics))
    for topic in args.topics:
        msg_type = next(type(m) for t, m, _ in messages if t == topic)
        publishers[topic] = rospy.Publisher(topic, msg_type, queue_size=100000)
    wait_for(lambda: all(p.get_num_connections() > 0 for p in publishers.values()) and recorder.connected(),
             args.connect_timeout, "the node to subscribe and publish")

    start_wall = time.monotonic()
    start_bag = messages[0][2].to_sec()
    for topic, msg, t in messages:
        delay = start_wall + (t.to_sec() - start_bag) / args.speed - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        publishers[topic].publish(msg)
    wait_for(lambda: time.monotonic() - recorder.last_message > args.quiet, 600.0, "the node's outputs to end")
    recorder.write(args.out_dir)
    bag.close()
    rospy.signal_shutdown("done")


if __name__ == "__main__":
    main()
