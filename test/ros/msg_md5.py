#!/usr/bin/python3
"""Prints the MD5 sum genmsg computes for a message type from its full definition (a file in
gencpp's concatenated form), the way rosbag and genpy build a type they have no package for.
Usage: msg_md5.py TYPE FILE"""
import sys

import genpy.dynamic

type_name, path = sys.argv[1], sys.argv[2]
with open(path) as definition:
    classes = genpy.dynamic.generate_dynamic(type_name, definition.read())
print(classes[type_name]._md5sum)
