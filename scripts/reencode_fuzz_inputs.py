#!/usr/bin/python3
"""Writes saved fuzz inputs of a ROS message again in today's layout of the message.

test_fuzz_regressions replays test/fuzz_regressions/<target>/ as serialised messages; when a
message in msg/ changes, those bytes misparse (they may declare huge arrays) and the test's
layout check fails. This decodes each input with the message definitions of the commit it was
saved at, copies every field that still exists by name (new fields keep their defaults, listed),
and writes it in the working tree's layout. Then update test/fuzz_regressions/layouts.txt.

  scripts/reencode_fuzz_inputs.py --commit OLD --message MappingJobMsg \
      test/fuzz_regressions/fuzz_mapping_job_msg/*
"""
import argparse
import importlib
import io
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GENMSG = '/usr/lib/genpy/genmsg_py.py'
INCLUDES = ['-Istd_msgs:/usr/share/std_msgs/msg', '-Isensor_msgs:/usr/share/sensor_msgs/msg',
            '-Igeometry_msgs:/usr/share/geometry_msgs/msg']


def generate(msg_dir, out_dir):
    """Python classes for every message in msg_dir, as package ply_slam under out_dir."""
    package = os.path.join(out_dir, 'ply_slam')
    os.makedirs(os.path.join(package, 'msg'))
    open(os.path.join(package, '__init__.py'), 'w').close()
    for name in sorted(os.listdir(msg_dir)):
        if name.endswith('.msg'):
            subprocess.run([sys.executable, GENMSG, '-p', 'ply_slam', '-Iply_slam:' + msg_dir] +
                           INCLUDES + ['-o', os.path.join(package, 'msg'),
                                       os.path.join(msg_dir, name)], check=True,
                           stdout=subprocess.DEVNULL)
    subprocess.run([sys.executable, GENMSG, '--initpy', '-p', 'ply_slam', '-o',
                    os.path.join(package, 'msg')], check=True, stdout=subprocess.DEVNULL)


def message_class(py_dir, name):
    for module in [m for m in sys.modules if m == 'ply_slam' or m.startswith('ply_slam.')]:
        del sys.modules[module]
    sys.path.insert(0, py_dir)
    try:
        return getattr(importlib.import_module('ply_slam.msg'), name)
    finally:
        sys.path.pop(0)


def copy_fields(old, new_class, path=''):
    """A new_class message with old's fields that new_class still has; prints those it lacks."""
    new = new_class()
    for slot, kind in zip(new_class.__slots__, new_class._slot_types):
        if slot not in old.__slots__:
            print('  %s%s: new, left at its default' % (path, slot))
            continue
        value = getattr(old, slot)
        if hasattr(getattr(new, slot), '__slots__'):  # a message: field by field
            value = copy_fields(value, type(getattr(new, slot)), path + slot + '.')
        elif isinstance(value, list) and value and hasattr(value[0], '__slots__'):
            element = message_type(kind.split('[')[0])
            value = [copy_fields(v, element, '%s%s[].' % (path, slot)) for v in value]
        setattr(new, slot, value)
    return new


def message_type(name):
    """'package/Type' as today's definitions have it (ply_slam's: the last generated)."""
    package, type_name = name.split('/')
    return getattr(importlib.import_module(package + '.msg'), type_name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--commit', required=True, help='the commit the inputs were saved at')
    parser.add_argument('--message', required=True, help='e.g. MappingJobMsg')
    parser.add_argument('inputs', nargs='+')
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        old_msg = os.path.join(tmp, 'old_msg')
        os.makedirs(old_msg)
        listing = subprocess.run(['git', '-C', ROOT, 'ls-tree', '--name-only', args.commit, 'msg/'],
                                 check=True, capture_output=True, text=True).stdout.split()
        for path in listing:
            if path.endswith('.msg'):
                text = subprocess.run(['git', '-C', ROOT, 'show', '%s:%s' % (args.commit, path)],
                                      check=True, capture_output=True).stdout
                open(os.path.join(old_msg, os.path.basename(path)), 'wb').write(text)
        generate(old_msg, os.path.join(tmp, 'old'))
        generate(os.path.join(ROOT, 'msg'), os.path.join(tmp, 'new'))
        old_class = message_class(os.path.join(tmp, 'old'), args.message)
        decoded = []
        for path in args.inputs:
            message = old_class()
            message.deserialize(open(path, 'rb').read())
            decoded.append((path, message))
        new_class = message_class(os.path.join(tmp, 'new'), args.message)
        for path, message in decoded:
            print(path)
            out = io.BytesIO()
            copy_fields(message, new_class).serialize(out)
            new_class().deserialize(out.getvalue())  # reads back in today's layout
            open(path, 'wb').write(out.getvalue())


if __name__ == '__main__':
    main()
