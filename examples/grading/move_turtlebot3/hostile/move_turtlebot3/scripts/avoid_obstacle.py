#!/usr/bin/env python3
# Hostile: spins the CPU before it ever starts a node.
while True:
    pass
