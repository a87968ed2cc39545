"""Messages serialised once and patched in place: the bytes rospy sends, without building and
serialising a whole message for every publish.

A message whose layout never changes (fixed strings, fixed array lengths) is serialised once by
its own genpy class; the fields that change are then written into those bytes at their offsets,
found by serialising the message with a distinct marker value in each of them. What goes on the
wire is byte for byte what genpy would write (the unit tests compare them), with the same type and
md5 sum: a prebuilt message is an instance of a subclass of the message class.
"""
import io
import struct

import numpy as np

_HEADER_SEQ = struct.Struct('<I')
_FORMATS = {'d': struct.Struct('<d'), 'f': struct.Struct('<f'), 'I': struct.Struct('<I'),
            'i': struct.Struct('<i')}


def _get(message, path):
    for part in path.split('.'):
        message = message[int(part)] if part.isdigit() else getattr(message, part)
    return message


def _set(message, path, value):
    parent, _, last = path.rpartition('.')
    target = _get(message, parent) if parent else message
    if last.isdigit():
        target[int(last)] = value
    else:
        setattr(target, last, value)


def _marker(kind, index):
    """A value unlikely to occur anywhere else in a serialised message."""
    if kind in 'df':
        return (1.0 + index / 64.0) * 2.0 ** -100
    return 0x5EED0000 + index


def _offset(message, path, kind, index):
    original = _get(message, path)
    marker = _marker(kind, index)
    _set(message, path, marker)
    buffer = _serialised(message)
    _set(message, path, original)
    packed = _FORMATS[kind].pack(marker)
    offset = buffer.find(packed)
    if offset < 0 or buffer.find(packed, offset + 1) >= 0:
        raise ValueError('cannot locate field %s of %s' % (path, message._type))
    return offset


def _serialised(message):
    buffer = io.BytesIO()
    message.serialize(buffer)
    return buffer.getvalue()


def prebuilt(message, fields, array=None):
    """A message of `message`'s type and contents, whose `fields` (a list of
    (dotted path, struct format 'd', 'f', 'I' or 'i')) update() writes in this order; `array`,
    (dotted path of a float32 array, length), is what write_array() fills (a LaserScan's ranges).
    Strings and array lengths are those of `message` for good."""
    message_class = type(message)
    packers = [(_FORMATS[kind], _offset(message, path, kind, index))
               for index, (path, kind) in enumerate(fields)]
    array_offset = None
    if array is not None:
        path, length = array
        original = _get(message, path)
        _set(message, path, [_marker('f', 63)] + [0.0] * (length - 1))
        array_offset = _serialised(message).find(_FORMATS['f'].pack(_marker('f', 63)))
        _set(message, path, original)
        if array_offset < 0:
            raise ValueError('cannot locate array %s of %s' % (path, message._type))
    # A class per message: it holds that message's bytes. Its methods are the class's own, and
    # genpy still finds the fields in the message class's __slots__.
    subclass = type('Prebuilt' + message_class.__name__, (message_class,),
                    dict(_METHODS, _data=bytearray(_serialised(message)),
                         _packers=packers, _array_offset=array_offset))
    return subclass(**{slot: getattr(message, slot) for slot in message_class.__slots__})


class PrebuiltMessage:
    """The methods of a prebuilt message class: serialize() writes the prebuilt bytes. The
    message's own fields stay those it was built from (rospy keeps the header's seq up to date);
    update() and write_array() change only the bytes."""

    def update(self, *values):
        data = self._data
        for (packer, offset), value in zip(self._packers, values):
            packer.pack_into(data, offset, value)

    def write_array(self, values):
        """Float32 values (as many as the prebuilt array holds) into the array's bytes."""
        floats = np.asarray(values, dtype='<f4')
        self._data[self._array_offset:self._array_offset + 4 * len(floats)] = floats.tobytes()

    def serialize(self, buff):
        if self._has_header:
            _HEADER_SEQ.pack_into(self._data, 0, self.header.seq & 0xFFFFFFFF)
        buff.write(self._data)

    def serialized(self):
        """The bytes serialize() writes."""
        return bytes(self._data)


_METHODS = {name: value for name, value in vars(PrebuiltMessage).items() if not name.startswith('__')}
