"""What a page may send, who may connect, and how fast keys may come (pure, milliseconds)."""
import json
import struct

import pytest

from course_web.origin import host_allowed, origin_allowed
from course_web.pacing import KeyBudget
from course_web.protocol import MAX_MESSAGE_BYTES, ProtocolError, parse_client_message, websocket_text_frame


@pytest.mark.parametrize('key', ['ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight', 'w', 'a', 's', 'd', 'x', ' '])
def test_the_teleops_keys_are_accepted(key):
    assert parse_client_message(json.dumps({'key': key})) == key


@pytest.mark.parametrize('message, reason', [
    (b'\x00\x01', 'binary'),
    ('{"key": "w"' + ' ' * MAX_MESSAGE_BYTES + '}', 'bytes (at most'),
    ('not json', 'not JSON'),
    ('[1, 2]', 'expected {"key": NAME}'),
    ('{"key": "w", "topic": "/cmd_vel"}', 'expected {"key": NAME}'),
    ('{"topic": "/turtle1/cmd_vel", "linear": 100}', 'expected {"key": NAME}'),
    ('{"key": "q"}', 'unknown key'),
    ('{"key": 3}', 'unknown key'),
    ('{"key": null}', 'unknown key'),
    ('{"key": "W"}', 'unknown key'),
    ('"w"', 'expected {"key": NAME}'),
    ('{"key": "\\ud800"}', 'unknown key'),
])
def test_anything_else_is_refused_with_a_reason(message, reason):
    with pytest.raises(ProtocolError, match=reason.replace('(', r'\(').replace('[', r'\[')):
        parse_client_message(message)


def test_same_origin_pages_may_connect():
    assert origin_allowed('http://localhost:8080', 'localhost:8080')
    assert origin_allowed('http://127.0.0.1:8080', '127.0.0.1:8080')
    assert origin_allowed('http://[::1]:8080', '[::1]:8080')
    assert origin_allowed('http://192.168.1.20:9000', '192.168.1.20:9000')
    assert origin_allowed('http://labserver:8080', 'labserver:8080', allowed_names=('labserver',))


@pytest.mark.parametrize('origin, host', [
    ('http://evil.example', 'localhost:8080'),          # another site in the same browser
    ('http://localhost:8081', 'localhost:8080'),        # another local server
    ('https://localhost:8080.evil.example', 'localhost:8080'),
    ('null', 'localhost:8080'),                          # a sandboxed frame or a file:// page
    ('file://', 'localhost:8080'),
    (None, 'localhost:8080'),                            # no Origin at all
    ('', 'localhost:8080'),
    ('http://evil.example:8080', 'evil.example:8080'),  # DNS rebinding: same origin, foreign name
    ('http://localhost:8080/path', 'localhost:8080'),
])
def test_other_origins_may_not(origin, host):
    assert not origin_allowed(origin, host)


def test_hosts_are_loopback_names_addresses_or_allowed_names():
    assert host_allowed('localhost:8080') and host_allowed('LOCALHOST') and host_allowed('127.0.0.1')
    assert host_allowed('[::1]:80') and host_allowed('10.0.0.5:8080') and host_allowed('app.localhost:1')
    assert not host_allowed('evil.example:8080')
    assert not host_allowed('')
    assert not host_allowed('localhost:80x')
    assert host_allowed('labserver:8080', ('labserver',)) and not host_allowed('labserver:8080')


def test_a_held_key_passes_and_a_flood_does_not():
    budget = KeyBudget(rate=40, burst=40)
    held = [budget.allow(i / 30.0) for i in range(300)]  # 30 presses a second for 10 s
    assert all(held)
    flood = KeyBudget(rate=40, burst=40)
    passed = sum(flood.allow(1.0 + i * 1e-4) for i in range(10000))  # 10 000 presses in 1 s
    assert 40 <= passed <= 85
    assert flood.refused == 10000 - passed


def read_websocket_message(data):
    """(FIN, opcode, masked, payload) of one websocket message, as RFC 6455 5.2 lays it out."""
    fin, opcode, masked, size = data[0] >> 7, data[0] & 0x0f, data[1] >> 7, data[1] & 0x7f
    start = 2
    if size == 126:
        size, start = struct.unpack('!H', data[2:4])[0], 4
    elif size == 127:
        size, start = struct.unpack('!Q', data[2:10])[0], 10
    assert len(data) == start + size  # nothing before or after the message
    return fin, opcode, masked, data[start:]


@pytest.mark.parametrize('text', ['', '{"a":1}', 'x' * 125, 'é' * 63, 'y' * 126, 'z' * 65535, 'w' * 65536,
                                  '{"scan":[%s]}' % ','.join(['[1.234,-5.678]'] * 10000)])
def test_a_frame_goes_out_as_one_websocket_text_message(text):
    assert read_websocket_message(websocket_text_frame(text)) == (1, 1, 0, text.encode('utf-8'))
