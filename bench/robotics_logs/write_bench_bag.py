#!/usr/bin/python3
"""Writes the ROS 1 bag of bench/robotics_read.sh with ROS's own writer (Debian's python3-rosbag).

    write_bench_bag.py SECONDS RATE_HZ COMPRESSION OUT.bag

One topic /imu (sensor_msgs/Imu) of SECONDS x RATE_HZ messages, stamps on an exact grid from an
epoch beyond 2^53 ns, record time 2.5 ms later; values pseudo-random (fixed seed). COMPRESSION is
none, bz2 or lz4 (rosbag's default chunk threshold of 768 KiB, as `rosbag record`).
"""
import random
import sys

import rosbag
import rospy
from sensor_msgs.msg import Imu

START_NS = 1_700_000_000_123_456_789


def main(seconds, rate_hz, compression, path):
    rng = random.Random(7)
    count = int(round(seconds * rate_hz))
    period_ns = round(1e9 / rate_hz)
    m = Imu()
    m.header.frame_id = "imu_link"
    m.orientation.w = 1.0
    m.orientation_covariance = [-1.0] + [0.0] * 8
    m.angular_velocity_covariance = [1e-6 * (k + 1) for k in range(9)]
    m.linear_acceleration_covariance = [1e-4 * (k + 1) for k in range(9)]
    g = rng.gauss
    with rosbag.Bag(path, "w", compression=compression) as bag:
        for i in range(count):
            stamp = START_NS + i * period_ns
            m.header.seq = i
            m.header.stamp = rospy.Time(stamp // 1_000_000_000, stamp % 1_000_000_000)
            av, la = m.angular_velocity, m.linear_acceleration
            av.x, av.y, av.z = 0.01 * g(0, 1), 0.01 * g(0, 1), 0.01 * g(0, 1)
            la.x, la.y, la.z = 0.02 * g(0, 1), 0.02 * g(0, 1), 9.80665 + 0.02 * g(0, 1)
            log = stamp + 2_500_000
            bag.write("/imu", m, rospy.Time(log // 1_000_000_000, log % 1_000_000_000))


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit("usage: write_bench_bag.py SECONDS RATE_HZ none|bz2|lz4 OUT.bag")
    main(float(sys.argv[1]), float(sys.argv[2]), sys.argv[3], sys.argv[4])
