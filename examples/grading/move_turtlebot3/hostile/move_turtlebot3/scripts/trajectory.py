#!/usr/bin/env python3
# Hostile: forks as many processes as it can, then prints without end.
import os
import time

children = 0
try:
    for _ in range(100000):
        if os.fork() == 0:
            time.sleep(3600)
            os._exit(0)
        children += 1
except OSError as error:
    print('fork failed after %d children: %s' % (children, error), flush=True)
while True:
    print('spam ' * 20)
