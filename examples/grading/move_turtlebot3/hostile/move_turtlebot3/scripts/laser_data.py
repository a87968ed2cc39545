#!/usr/bin/env python3
# Hostile: writes outside its folder, opens connections, then fills its disk.
import os
import socket

for path in ('/home/student/course/src/hostile_was_here', os.path.expanduser('~/hostile_was_here'),
             os.path.join(os.path.dirname(os.path.abspath(__file__)), 'hostile_was_here'),
             '/submission/hostile_was_here', '/out/../hostile_was_here'):
    try:
        with open(path, 'w') as stream:
            stream.write('hostile\n')
        print('wrote', path, flush=True)
    except OSError as error:
        print('could not write %s: %s' % (path, error), flush=True)
for address in (('1.1.1.1', 53), ('example.com', 80)):
    try:
        socket.create_connection(address, timeout=3).close()
        print('connected to', address, flush=True)
    except OSError as error:
        print('could not connect to %s: %s' % (address, error), flush=True)
number = 0
while True:
    try:
        with open('/tmp/fill%d' % number, 'wb') as stream:
            for _ in range(64):       # files of 64 MB, many of them
                stream.write(b'x' * 2 ** 20)
        number += 1
    except OSError as error:
        print('disk full after %d files: %s' % (number, error), flush=True)
        break
while True:
    pass
