"""Who may open the page and its websocket (pure).

A page from another site open in the same browser must not drive the robot: the websocket's
Origin must be this server itself (same scheme, host and port as the request's Host). And the
Host itself must be a name we answer to (loopback names, an IP address, or one the user allowed),
so that a foreign site cannot rename itself to our address (DNS rebinding) and pass as same-origin.
"""
import ipaddress
from urllib.parse import urlsplit

LOOPBACK_NAMES = ('localhost',)


def split_host(host):
    """(name, port or None) of a Host header value such as 'localhost:8080' or '[::1]:80'."""
    host = host.strip().lower()
    if host.startswith('['):
        name, _, rest = host[1:].partition(']')
        port = rest[1:] if rest.startswith(':') else None
    elif host.count(':') == 1:
        name, port = host.split(':')
    else:
        name, port = host, None
    return name, port


def host_allowed(host, allowed_names=()):
    """True if a Host header names this server: localhost, an IP address, or an allowed name."""
    if not host:
        return False
    name, port = split_host(host)
    if port is not None and not port.isdigit():
        return False
    if name in LOOPBACK_NAMES or name.endswith('.localhost') or name in allowed_names:
        return True
    try:
        ipaddress.ip_address(name)
    except ValueError:
        return False
    return True


def origin_allowed(origin, host, allowed_names=()):
    """True if a websocket's Origin header is the page this server served (and the Host is ours)."""
    if not origin or not host_allowed(host, allowed_names):
        return False
    parts = urlsplit(origin.strip().lower())
    if parts.scheme not in ('http', 'https') or not parts.netloc or parts.path not in ('', '/'):
        return False
    return split_host(parts.netloc) == split_host(host)
