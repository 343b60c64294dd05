"""Reads include/rle_vision/landmark_params.def, the one table of the landmark path's
parameters, for the .cfg files: each RLE_<GROUP>_PARAM(...) line becomes a dynamic_reconfigure
parameter with the same name, type, default, limits and description as the C++ core uses."""
import os
import re

TABLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'include', 'rle_vision',
                     'landmark_params.def')
_ENTRY = re.compile(r'^RLE_(\w+)_PARAM\(\s*(\w+),\s*(\w+),\s*(\w+),\s*([^,]+),\s*([^,]+),\s*([^,]+),'
                    r'\s*"((?:[^"\\]|\\.)*)"\s*\)\s*$')


def _value(text, cpp_type):
    text = text.strip()
    if cpp_type == 'bool':
        return {'true': True, 'false': False}[text]
    if cpp_type == 'double':
        return float(text)
    return int(text)


def entries(group):
    """(key, cpp_type, default, min, max, description) of every parameter of `group`."""
    found = []
    with open(TABLE) as table:
        for line in table:
            match = _ENTRY.match(line.strip())
            if match and match.group(1) == group:
                _, key, _member, cpp_type, default, lo, hi, description = match.groups()
                found.append((key, cpp_type, _value(default, cpp_type), _value(lo, cpp_type),
                              _value(hi, cpp_type), description.replace('\\"', '"')))
    if not found:
        raise RuntimeError('%s holds no RLE_%s_PARAM entries' % (TABLE, group))
    return found


def add_group(generator, group, ros_types):
    """Adds the parameters of `group` to a ParameterGenerator (or one of its groups)."""
    for key, cpp_type, default, lo, hi, description in entries(group):
        if cpp_type == 'bool':
            generator.add(key, ros_types['bool'], 0, description, default)
        else:
            generator.add(key, ros_types['double' if cpp_type == 'double' else 'int'], 0, description,
                          default, lo, hi)
