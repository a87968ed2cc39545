"""What a browser may send, and how frames go out (pure: no ROS, no web library).

A page sends one kind of message: a key press, as JSON {"key": NAME}, NAME being one of the keys
of turtle_teleop_key (the arrows) or of turtlebot3_teleop_key (w, a, s, d, x, space). Anything
else (binary, oversized, not JSON, other fields, other keys) is a ProtocolError: the server closes
that connection and logs one line.
"""
import json
import struct

MAX_MESSAGE_BYTES = 128  # a key message is about 20 bytes
# The web library itself refuses frames larger than this before they reach us (it closes with 1009).
MAX_TRANSPORT_BYTES = 4096

# turtle_teleop_key: arrow -> (linear, angular) before scaling by scale_linear / scale_angular
TURTLESIM_KEYS = {'ArrowUp': (1.0, 0.0), 'ArrowDown': (-1.0, 0.0),
                  'ArrowLeft': (0.0, 1.0), 'ArrowRight': (0.0, -1.0)}
# turtlebot3_teleop_key's keys, as the browser names them (KeyboardEvent.key)
TB3_KEYS = ('w', 'a', 's', 'd', 'x', ' ')


class ProtocolError(ValueError):
    """A message from a page that the server does not accept; the text says why."""


def parse_client_message(data):
    """The key name a page's message carries, or ProtocolError."""
    if isinstance(data, bytes):
        raise ProtocolError('binary message of %d bytes (only JSON text is accepted)' % len(data))
    size = len(data.encode('utf-8', 'surrogatepass'))
    if size > MAX_MESSAGE_BYTES:
        raise ProtocolError('message of %d bytes (at most %d)' % (size, MAX_MESSAGE_BYTES))
    try:
        message = json.loads(data)
    except ValueError:
        raise ProtocolError('message is not JSON: %r' % data[:40]) from None
    if not isinstance(message, dict) or set(message) != {'key'}:
        raise ProtocolError('expected {"key": NAME}, got %r' % data[:60])
    key = message['key']
    if not isinstance(key, str) or (key not in TURTLESIM_KEYS and key not in TB3_KEYS):
        raise ProtocolError('unknown key %r (arrows for turtlesim; w, a, s, d, x, space for '
                            'the TurtleBot3)' % (key,))
    return key


def encode_frame(parts):
    """One frame for the page: a JSON object text, compact."""
    return json.dumps(parts, separators=(',', ':'), allow_nan=False)


def websocket_text_frame(text):
    """A frame's text as the bytes of one websocket text message from a server (RFC 6455 5.2: FIN
    and opcode 1, the length in 7, 16 or 64 bits, no mask), made once for every page that gets it."""
    data = text.encode('utf-8')
    size = len(data)
    if size < 126:
        return bytes((0x81, size)) + data
    if size < 1 << 16:
        return struct.pack('!BBH', 0x81, 126, size) + data
    return struct.pack('!BBQ', 0x81, 127, size) + data
