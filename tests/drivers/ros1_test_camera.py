#!/usr/bin/python3
"""A stereo camera for the ROS 1 camera tests (ros1_camera_test.py): a rospy node publishing a
left and a right image, optionally with camera_info, for what Debian's image_publisher cannot
do: compressed topics (no image_transport plugins are packaged), encodings other than bgr8,
stamps in the past or apart by a chosen offset.

    ros1_test_camera.py --left TOPIC --right TOPIC [--encoding rgb8|bgr8|mono8|bayer_rggb8]
        [--format jpeg|png] [--rate HZ] [--age-ms MS] [--right-offset-ms MS] [--periodic-stamps]
        [--left-info YAML --right-info YAML] [--log FILE]

A topic ending in /compressed gets sensor_msgs/CompressedImage in --format, any other
sensor_msgs/Image in --encoding. The scenes are test_scene("left") and test_scene("right").
Each frame's left stamp is ROS time now less --age-ms, the right one that plus
--right-offset-ms; --log gets one JSON line per frame: the left stamp and this machine's
CLOCK_MONOTONIC at the moment the stamp was taken (ns). Prints "camera ready" once advertised.
"""

import argparse
import io
import json
import time

import rospy
import yaml
from PIL import Image as PilImage
from sensor_msgs.msg import CameraInfo, CompressedImage, Image

WIDTH, HEIGHT = 320, 240
# The two scenes, as (region test, RGB): the left eye red over green, the right blue beside
# yellow, so a swapped eye or swapped channels show.
LEFT_TOP, LEFT_BOTTOM = (220, 30, 30), (30, 220, 30)
RIGHT_LEFT, RIGHT_RIGHT = (30, 30, 220), (230, 230, 30)


def test_scene(eye):
    image = PilImage.new("RGB", (WIDTH, HEIGHT))
    if eye == "left":
        image.paste(LEFT_TOP, (0, 0, WIDTH, HEIGHT // 2))
        image.paste(LEFT_BOTTOM, (0, HEIGHT // 2, WIDTH, HEIGHT))
    else:
        image.paste(RIGHT_LEFT, (0, 0, WIDTH // 2, HEIGHT))
        image.paste(RIGHT_RIGHT, (WIDTH // 2, 0, WIDTH, HEIGHT))
    return image


def bayer_rggb(image):
    """The RGGB mosaic of an RGB image: R at even rows and columns, B at odd ones."""
    rgb = image.tobytes()
    out = bytearray(WIDTH * HEIGHT)
    for y in range(HEIGHT):
        for x in range(WIDTH):
            channel = 0 if (y % 2, x % 2) == (0, 0) else 2 if (y % 2, x % 2) == (1, 1) else 1
            out[y * WIDTH + x] = rgb[3 * (y * WIDTH + x) + channel]
    return bytes(out)


def raw_message(image, encoding):
    message = Image(width=WIDTH, height=HEIGHT, encoding=encoding, is_bigendian=0)
    if encoding == "rgb8":
        message.data, message.step = image.tobytes(), WIDTH * 3
    elif encoding == "bgr8":
        r, g, b = image.split()
        message.data, message.step = PilImage.merge("RGB", (b, g, r)).tobytes(), WIDTH * 3
    elif encoding == "mono8":
        message.data, message.step = image.convert("L").tobytes(), WIDTH
    elif encoding == "bayer_rggb8":
        message.data, message.step = bayer_rggb(image), WIDTH
    else:
        raise SystemExit(f"ros1_test_camera: encoding {encoding} is not one of this camera's")
    return message


def compressed_message(image, image_format):
    data = io.BytesIO()
    image.save(data, format="JPEG" if image_format == "jpeg" else "PNG", quality=95)
    return CompressedImage(format=image_format, data=data.getvalue())


def camera_info(path):
    with open(path) as f:
        c = yaml.safe_load(f)
    return CameraInfo(width=c["image_width"], height=c["image_height"],
                      distortion_model=c["distortion_model"],
                      D=c["distortion_coefficients"]["data"], K=c["camera_matrix"]["data"],
                      R=c["rectification_matrix"]["data"], P=c["projection_matrix"]["data"])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--left", required=True)
    parser.add_argument("--right", required=True)
    parser.add_argument("--encoding", default="rgb8")
    parser.add_argument("--format", default="jpeg", choices=["jpeg", "png"])
    parser.add_argument("--rate", type=float, default=20.0)
    parser.add_argument("--age-ms", type=float, default=0.0)
    parser.add_argument("--right-offset-ms", type=float, default=0.0)
    parser.add_argument("--left-info")
    parser.add_argument("--right-info")
    parser.add_argument("--log")
    parser.add_argument("--periodic-stamps", action="store_true",
                        help="stamps exactly 1/rate apart (from the first), not the clock's "
                             "reading at each frame, which a loaded machine makes jitter")
    args = parser.parse_args()

    rospy.init_node("telear_test_camera", anonymous=True)
    eyes = []
    for eye, topic, info_path in (("left", args.left, args.left_info),
                                  ("right", args.right, args.right_info)):
        compressed = topic.endswith("/compressed")
        message = (compressed_message(test_scene(eye), args.format) if compressed
                   else raw_message(test_scene(eye), args.encoding))
        publisher = rospy.Publisher(topic, CompressedImage if compressed else Image, queue_size=2)
        info = info_publisher = None
        if info_path:
            info = camera_info(info_path)
            base = topic[:-len("/compressed")] if compressed else topic
            info_topic = base.rsplit("/", 1)[0] + "/camera_info"
            info_publisher = rospy.Publisher(info_topic, CameraInfo, queue_size=2)
        eyes.append((message, publisher, info, info_publisher))
    log = open(args.log, "a") if args.log else None
    print("camera ready", flush=True)

    period = 1.0 / args.rate
    age = rospy.Duration.from_sec(args.age_ms * 1e-3)
    offset = rospy.Duration.from_sec(args.right_offset_ms * 1e-3)
    next_time = time.monotonic()
    first_stamp = rospy.Time.now() - age
    frame_number = 0
    while not rospy.is_shutdown():
        monotonic_ns = time.clock_gettime_ns(time.CLOCK_MONOTONIC)
        stamp = rospy.Time.now() - age
        if args.periodic_stamps:
            stamp = first_stamp + rospy.Duration.from_sec(frame_number * period)
        frame_number += 1
        for k, (message, publisher, info, info_publisher) in enumerate(eyes):
            message.header.stamp = stamp + offset if k == 1 else stamp
            publisher.publish(message)
            if info is not None:
                info.header.stamp = message.header.stamp
                info_publisher.publish(info)
        if log:
            frame = {"stamp_ns": stamp.to_nsec(), "monotonic_ns": monotonic_ns}
            log.write(json.dumps(frame) + "\n")
            log.flush()
        next_time += period
        time.sleep(max(0.0, next_time - time.monotonic()))


if __name__ == "__main__":
    main()
