#!/usr/bin/python3
"""Writes the seeds of the ros_camera_info harness (fuzz/ros_camera_info_fuzz.cpp) in its
fuzz::ByteReader layout: two camera_info messages' fields, then the two image topics' sizes.

Usage: fuzz/seeds/camera_info.py fuzz/corpus/ros_camera_info
"""

import os
import struct
import sys


def text(s):
    b = s.encode()
    return struct.pack("<B", len(b)) + b


def camera_info(topic, frame, w, h, model, D, K, R, P, binning=(0, 0), roi=(0, 0, 0, 0)):
    out = text(topic) + text(frame) + struct.pack("<ii", w, h) + text(model)
    out += struct.pack("<B", len(D)) + struct.pack("<%dd" % len(D), *D)
    out += struct.pack("<9d", *K) + struct.pack("<9d", *R) + struct.pack("<12d", *P)
    out += struct.pack("<ii", *binning) + struct.pack("<iiii", *roi)
    return out


def pair(left, right, sizes):
    return left + right + struct.pack("<iiii", *sizes)


K = [500, 0, 319.5, 0, 500, 239.5, 0, 0, 1]
I3 = [1, 0, 0, 0, 1, 0, 0, 0, 1]
P_LEFT = [500, 0, 319.5, 0, 0, 500, 239.5, 0, 0, 0, 1, 0]
P_RIGHT = [500, 0, 319.5, -30.0, 0, 500, 239.5, 0, 0, 0, 1, 0]  # Tx = -fx * 0.06 m
PLUMB = [-0.1, 0.01, 0.0, 0.0, 0.0]

SEEDS = {
    "rectified_pair": pair(
        camera_info("/left/image_raw", "left", 640, 480, "plumb_bob", PLUMB, K, I3, P_LEFT),
        camera_info("/right/image_raw", "right", 640, 480, "plumb_bob", PLUMB, K, I3, P_RIGHT),
        (640, 480, 640, 480)),
    "not_a_pair": pair(
        camera_info("/l", "l", 640, 480, "rational_polynomial", PLUMB + [0, 0, 0], K, I3, P_LEFT),
        camera_info("/r", "r", 640, 480, "rational_polynomial", PLUMB + [0, 0, 0], K, I3, P_LEFT),
        (640, 480, 640, 480)),
    "equidistant": pair(
        camera_info("/l", "l", 800, 600, "equidistant", [0.1, 0.01, 0, 0], K, I3, P_LEFT),
        camera_info("/r", "r", 800, 600, "equidistant", [0.1, 0.01, 0, 0], K, I3, P_RIGHT),
        (800, 600, 800, 600)),
    "uncalibrated": pair(
        camera_info("/l", "l", 640, 480, "", [], [0] * 9, [0] * 9, [0] * 12),
        camera_info("/r", "r", 640, 480, "", [], [0] * 9, [0] * 9, [0] * 12),
        (640, 480, 640, 480)),
    "binned_with_roi": pair(
        camera_info("/l", "l", 320, 240, "plumb_bob", PLUMB, K, I3, P_LEFT, (2, 2), (10, 10, 300, 200)),
        camera_info("/r", "r", 640, 480, "plumb_bob", PLUMB, K, I3, P_RIGHT),
        (320, 240, 1280, 720)),
}

if __name__ == "__main__":
    folder = sys.argv[1]
    os.makedirs(folder, exist_ok=True)
    for name, data in SEEDS.items():
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data)
