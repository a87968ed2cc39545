"""Network scenarios shared by tests/network/ and bench/resilience.py: masters on free ports, probes
that record a topic from a process of their own, faults, floods and two hosts in network namespaces.
probe.py, flood.py and calls.py are run as programs."""
