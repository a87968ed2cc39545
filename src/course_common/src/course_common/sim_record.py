"""A simulator's own record of what it did, for the grader's judge: each entry says what (a name:
`pose`, `scan`, `command`, ...), when in simulated time (ns) and in wall time (time.monotonic(),
one clock for every process of the machine), and its bytes (a message as the simulator serialised
it, or a small JSON object).

The simulator, started by the trusted side, writes it to a file that only the trusted user can
open (mode 600, in the trusted side's folder); the judge reads it while the run goes on. What a
node publishes on the simulator's topics never reaches it, whatever name the node gives itself.
Pure: no ROS (course_common.sim_record_ros connects it to a node).

The entries (payloads: a message's bytes, or a JSON event's fields):
- fake_tb3: `pose` (PREFIXpose, struct '<5d': x, y, yaw, linear, angular, at each odometry),
  `scan` (PREFIXscan: the LaserScan as sent, but for the header's sequence number), `command`
  {robot, linear, angular, sender, nodes} as applied, `collisions` {robot, count} at each change,
  `service_call` {service, caller};
- turtlesim: `/TURTLE/pose` (its pose topic's resolved name: the turtlesim/Pose bytes, every tick),
  `turtles` {names} when they change, `command` {turtle, linear, angular, sender, nodes} as heard,
  `service_call` {service, caller}; and what a replay needs to redraw the trails as turtlesim drew
  them, at the tick they apply in: `pen` {turtle, r, g, b, width, off} at each set_pen, `clear`
  {background} at the first tick and at each /clear and /reset (course_grader.bags makes a rosbag
  of each run from these).

Also here: the user id that owns the other end of a TCP connection on this machine, as the kernel
tells it (/proc/net/tcp): who sent a command, without believing what the sender says of itself."""
import ipaddress
import json
import os
import struct
import threading

# wall time s, simulated time ns, length of the name, length of the payload; then both.
FRAME = struct.Struct('<dqHI')
ENVIRONMENT = 'COURSE_SIM_RECORD'   # the file a simulator records into, when the grader sets it


class Entry:
    __slots__ = ('name', 'sim_ns', 'wall', 'payload')

    def __init__(self, name, sim_ns, wall, payload):
        self.name, self.sim_ns, self.wall, self.payload = name, sim_ns, wall, payload

    @property
    def sim_time(self):
        """Simulated time in seconds."""
        return self.sim_ns * 1e-9

    def fields(self):
        """The payload of an event (written by RecordWriter.event) as a dict."""
        return json.loads(self.payload.decode())


class RecordWriter:
    """Appends entries to a new file (never one that exists, never through a link), thread-safe.
    Buffered: flush() when the readers should see what came so far."""

    def __init__(self, path):
        descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC,
                             0o600)
        self._stream = os.fdopen(descriptor, 'wb', buffering=1 << 16)
        self._lock = threading.Lock()

    def write(self, name, sim_ns, wall, payload):
        encoded = name.encode()
        with self._lock:
            self._stream.write(FRAME.pack(wall, sim_ns, len(encoded), len(payload)))
            self._stream.write(encoded)
            self._stream.write(payload)

    def event(self, name, sim_ns, wall, **fields):
        """An entry whose payload is `fields` as JSON (a command, a service call)."""
        self.write(name, sim_ns, wall, json.dumps(fields, sort_keys=True).encode())

    def flush(self):
        with self._lock:
            self._stream.flush()

    def close(self):
        with self._lock:
            self._stream.close()


class RecordReader:
    """The entries of a record as they come: read_new() returns those completed since its last
    call (none while the file does not exist yet)."""

    def __init__(self, path):
        self.path = path
        self._offset = 0
        self._pending = b''

    def read_new(self):
        try:
            descriptor = os.open(self.path, os.O_RDONLY | os.O_NOFOLLOW | os.O_CLOEXEC)
        except FileNotFoundError:
            return []
        with os.fdopen(descriptor, 'rb') as stream:
            stream.seek(self._offset)
            data = stream.read()
        self._offset += len(data)
        data, entries, at = self._pending + data, [], 0
        while len(data) - at >= FRAME.size:
            wall, sim_ns, name_size, payload_size = FRAME.unpack_from(data, at)
            end = at + FRAME.size + name_size + payload_size
            if end > len(data):
                break
            name_end = at + FRAME.size + name_size
            entries.append(Entry(data[at + FRAME.size:name_end].decode(), sim_ns, wall, data[name_end:end]))
            at = end
        self._pending = data[at:]
        return entries


def _address(text):
    """(ip address, port) of /proc/net/tcp's hexadecimal 'ADDRESS:PORT' (the address in the
    kernel's byte order: 32-bit words, each little-endian)."""
    host, port = text.split(':')
    raw = bytes.fromhex(host)
    swapped = b''.join(raw[i:i + 4][::-1] for i in range(0, len(raw), 4))
    address = ipaddress.ip_address(swapped)
    if address.version == 6 and address.ipv4_mapped:
        address = address.ipv4_mapped
    return address, int(port, 16)


def _endpoint(host, port):
    address = ipaddress.ip_address(host.split('%')[0])
    if address.version == 6 and address.ipv4_mapped:
        address = address.ipv4_mapped
    return address, port


def peer_uid(local, remote, tables=('/proc/net/tcp', '/proc/net/tcp6')):
    """The user id of the process at the other end of our TCP connection from `local` to `remote`
    ((host, port) each, as socket.getsockname() and getpeername() give them), as the kernel lists
    it; None where the kernel's tables cannot be read (no /proc) or list no such connection."""
    ours, theirs = _endpoint(*local[:2]), _endpoint(*remote[:2])
    for table in tables:
        try:
            with open(table) as stream:
                lines = stream.readlines()[1:]
        except OSError:
            continue
        for line in lines:
            fields = line.split()
            if len(fields) > 7 and _address(fields[1]) == theirs and _address(fields[2]) == ours:
                return int(fields[7])
    return None
