#!/usr/bin/python3
"""ROS's own bag library (Debian python3-rosbag, python3-sensor-msgs) on vilslam data, for the bag tests.

  rosbag_tool.py write DATASET OUT.bag [--left ENC] [--right ENC] [--lidar LAYOUT] [--compression C]
                   [--no-groundtruth]
      A dataset in vilslam's folder format as a bag, with ROS's message classes and writer.
      ENC: mono8 | rgb8 | bgr8 | mono16 (12 significant bits, the 8-bit value's bits repeated: v << 4 | v >> 4,
      little-endian) | mono16be (the same, big-endian) | png (sensor_msgs/CompressedImage) | any other name
      (written with mono8 bytes, to make a bag with a wrong encoding). LAYOUT: velodyne | ouster | hesai | livox | livox_offset.
      C: the chunks' compression, none | bz2 | lz4 (rosbag record --bz2 / --lz4).
  rosbag_tool.py dump BAG OUT.json
      Topics, types, counts, stamps and decoded values of a bag, as JSON.
Run with Debian's /usr/bin/python3 (the packages are not on other interpreters' paths).
"""
import csv
import json
import os
import struct
import sys
import zlib

import rosbag
import rospy
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import CompressedImage, Image, Imu, PointCloud2, PointField


def read_png_grey(path):
    """8-bit grey, non-interlaced PNG (what vilslam writes) -> (width, height, bytes)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 0 and interlace == 0, path
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    out = bytearray(width * height)
    prev = bytearray(width)
    for y in range(height):
        f = raw[y * (width + 1)]
        line = bytearray(raw[y * (width + 1) + 1:(y + 1) * (width + 1)])
        for x in range(width):
            a = line[x - 1] if x else 0
            b = prev[x]
            c = prev[x - 1] if x else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + pred) & 255
        out[y * width:(y + 1) * width] = line
        prev = line
    return width, height, bytes(out)


def rows(path):
    with open(path) as f:
        return [r for r in csv.reader(f) if r and not r[0].startswith("#")]


def stamp(t_ns):
    return rospy.Time(t_ns // 1000000000, t_ns % 1000000000)


def header(msg, t_ns, frame):
    msg.header.stamp = stamp(t_ns)
    msg.header.frame_id = frame


def image_message(folder, t_ns, name, encoding, frame):
    path = os.path.join(folder, "data", name)
    if encoding == "png":
        msg = CompressedImage()
        msg.format = "mono8; png compressed"
        msg.data = open(path, "rb").read()
    else:
        width, height, grey = read_png_grey(path)
        msg = Image()
        msg.width, msg.height, msg.encoding = width, height, encoding
        if encoding in ("rgb8", "bgr8"):
            msg.step = 3 * width
            msg.data = bytes(v for g in grey for v in (g, g, g))
        elif encoding in ("mono16", "mono16be"):
            msg.encoding, msg.is_bigendian, msg.step = "mono16", int(encoding == "mono16be"), 2 * width
            order = ">" if msg.is_bigendian else "<"
            msg.data = struct.pack(order + "%dH" % len(grey), *((g << 4) | (g >> 4) for g in grey))
        else:
            msg.step, msg.data = width, grey
    header(msg, t_ns, frame)
    return msg


def read_scan(path):
    data = open(path, "rb").read()
    assert data[:8] == b"VLSCAN01", path
    n, flags = struct.unpack("<II", data[8:16])
    points = [struct.unpack("<fffffHH", data[16 + 24 * i:40 + 24 * i])[:6] for i in range(n)]
    return points, bool(flags & 1)


F32, F64, U8, U16, U32 = PointField.FLOAT32, PointField.FLOAT64, PointField.UINT8, PointField.UINT16, PointField.UINT32
# (point_step, [(name, offset, datatype)]) as the drivers publish them.
LAYOUTS = {
    "velodyne": (22, [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 12, F32), ("ring", 16, U16),
                      ("time", 18, F32)]),
    "ouster": (48, [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 16, F32), ("t", 20, U32),
                    ("reflectivity", 24, U16), ("ring", 26, U16), ("ambient", 28, U16), ("range", 32, U32)]),
    "hesai": (48, [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 16, F32), ("timestamp", 24, F64),
                   ("ring", 32, U16)]),
    "livox": (26, [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 12, F32), ("tag", 16, U8),
                   ("line", 17, U8), ("timestamp", 18, F64)]),
    "livox_offset": (20, [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 12, F32),
                          ("offset_time", 16, U32)]),
}
PACK = {F32: "f", F64: "d", U8: "B", U16: "H", U32: "I"}


def cloud_message(path, t_ns, layout):
    points, _ = read_scan(path)
    step, fields = LAYOUTS[layout]
    data = bytearray(step * len(points))
    for i, (x, y, z, intensity, t_off, ring) in enumerate(points):
        values = {"x": x, "y": y, "z": z, "intensity": intensity, "ring": ring, "time": t_off,
                  "t": int(round(t_off * 1e9)), "offset_time": int(round(t_off * 1e9)),
                  "timestamp": t_ns * 1e-9 + t_off if layout == "hesai" else float(t_ns + int(round(t_off * 1e9))),
                  "reflectivity": 7, "ambient": 9, "range": 1234, "tag": 16, "line": ring % 6}
        for name, offset, kind in fields:
            struct.pack_into("<" + PACK[kind], data, step * i + offset, values[name])
    msg = PointCloud2()
    header(msg, t_ns, "lidar0")
    msg.height, msg.width = 1, len(points)
    msg.fields = [PointField(name=n, offset=o, datatype=k, count=1) for n, o, k in fields]
    msg.is_bigendian, msg.point_step, msg.row_step, msg.is_dense = False, step, step * len(points), True
    msg.data = bytes(data)
    return msg


def write(dataset, out, left="mono8", right="mono8", lidar="velodyne", compression="none", groundtruth=True):
    mav0 = os.path.join(dataset, "mav0")
    messages = []  # (t_ns, order, topic, msg)
    for r in rows(os.path.join(mav0, "imu0", "data.csv")):
        msg = Imu()
        header(msg, int(r[0]), "imu0")
        msg.orientation_covariance[0] = -1
        msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = map(float, r[1:4])
        msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = map(float, r[4:7])
        messages.append((int(r[0]), 0, "/imu0", msg))
    for cam, enc in (("cam0", left), ("cam1", right)):
        folder = os.path.join(mav0, cam)
        for r in rows(os.path.join(folder, "data.csv")):
            topic = "/%s/image_raw%s" % (cam, "/compressed" if enc == "png" else "")
            messages.append((int(r[0]), 2, topic, image_message(folder, int(r[0]), r[1].strip(), enc, cam)))
    lidar_dir = os.path.join(mav0, "lidar0")
    if os.path.isdir(lidar_dir):
        for r in rows(os.path.join(lidar_dir, "data.csv")):
            path = os.path.join(lidar_dir, "data", r[1].strip())
            messages.append((int(r[0]), 3, "/points_raw", cloud_message(path, int(r[0]), lidar)))
    gt_csv = os.path.join(mav0, "state_groundtruth_estimate0", "data.csv")
    if groundtruth and os.path.exists(gt_csv):
        for r in rows(gt_csv):
            msg = PoseStamped()
            header(msg, int(r[0]), "world")
            p, q = msg.pose.position, msg.pose.orientation
            p.x, p.y, p.z = map(float, r[1:4])
            q.w, q.x, q.y, q.z = map(float, r[4:8])
            messages.append((int(r[0]), 1, "/ground_truth", msg))
    messages.sort(key=lambda m: (m[0], m[1]))
    with rosbag.Bag(out, "w", compression=compression) as bag:
        for t_ns, _, topic, msg in messages:
            bag.write(topic, msg, stamp(max(t_ns, 1)))


def point_values(msg, count):
    names = {f.name: f for f in msg.fields}
    kinds = {PointField.INT8: "b", U8: "B", PointField.INT16: "h", U16: "H", PointField.INT32: "i", U32: "I",
             F32: "f", F64: "d"}
    out = []
    for i in range(min(count, msg.width * msg.height)):
        out.append({n: struct.unpack_from("<" + kinds[f.datatype], msg.data, i * msg.point_step + f.offset)[0]
                    for n, f in names.items()})
    return out


def dump(bag_path, out):
    topics = {}
    with rosbag.Bag(bag_path) as bag:
        info = bag.get_type_and_topic_info().topics
        for topic, msg, t in bag.read_messages():
            d = topics.setdefault(topic, {"type": info[topic].msg_type, "count": 0, "stamps": [], "record_times": [],
                                          "values": []})
            d["count"] += 1
            d["stamps"].append(msg.header.stamp.to_nsec())
            d["record_times"].append(t.to_nsec())
            kind = msg._type
            if kind == "sensor_msgs/Imu":
                d["values"].append([msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z,
                                    msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z,
                                    msg.orientation_covariance[0]])
            elif kind == "sensor_msgs/Image":
                d["values"].append({"encoding": msg.encoding, "width": msg.width, "height": msg.height,
                                    "step": msg.step, "frame_id": msg.header.frame_id, "pixel_sum": sum(msg.data),
                                    "first_pixels": list(msg.data[:8])})
            elif kind == "sensor_msgs/PointCloud2":
                d["values"].append({"fields": [[f.name, f.offset, f.datatype, f.count] for f in msg.fields],
                                    "point_step": msg.point_step, "width": msg.width, "height": msg.height,
                                    "is_bigendian": msg.is_bigendian, "points": point_values(msg, 3)})
            elif kind == "geometry_msgs/PoseStamped":
                p, q = msg.pose.position, msg.pose.orientation
                d["values"].append([p.x, p.y, p.z, q.x, q.y, q.z, q.w])
    with open(out, "w") as f:
        json.dump(topics, f)


def main(argv):
    if len(argv) >= 4 and argv[1] == "write":
        opts = {"left": "mono8", "right": "mono8", "lidar": "velodyne", "compression": "none", "groundtruth": True}
        args = argv[4:]
        while args:
            flag = args.pop(0)
            if flag == "--no-groundtruth":
                opts["groundtruth"] = False
            elif flag in ("--left", "--right", "--lidar", "--compression"):
                opts[flag[2:]] = args.pop(0)
            else:
                sys.exit("unknown option " + flag)
        write(argv[2], argv[3], **opts)
    elif len(argv) == 4 and argv[1] == "dump":
        dump(argv[2], argv[3])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
