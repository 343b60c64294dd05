"""Reads the nodes' parameter tables (include/rle_vision/params/*.def), the one source of each
node's parameters, for the .cfg files and the parameter reference (scripts/param_docs.py):
each RLE_<GROUP>_PARAM(...) line is a live-tunable parameter (a dynamic_reconfigure parameter
with the same name, type, default, limits and description as the C++ core uses), each
RLE_<NODE>_SETTING(...) line a parameter the node reads once at start."""
import os
import re

TABLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'include', 'rle_vision', 'params')
_PARAM = re.compile(r'^RLE_(\w+)_PARAM\(\s*(\w+),\s*(\w+),\s*([\w:]+),\s*([^,]+),\s*([^,]+),\s*([^,]+),'
                    r'\s*"((?:[^"\\]|\\.)*)"\s*\)\s*$')
_SETTING = re.compile(r'^RLE_(\w+)_SETTING\(\s*(\w+),\s*([\w:]+),\s*("(?:[^"\\]|\\.)*"|[^,]+),\s*([^,]+),\s*([^,]+),'
                      r'\s*"((?:[^"\\]|\\.)*)"\s*\)\s*$')


def _value(text, cpp_type):
    text = text.strip()
    if cpp_type == 'bool':
        return {'true': True, 'false': False}[text]
    if cpp_type == 'double':
        return float(text)
    if cpp_type == 'std::string':
        return text[1:-1].replace('\\"', '"')
    return int(text)


def _lines(table):
    with open(os.path.join(TABLES, table + '_params.def')) as f:
        return [line.strip() for line in f]


def entries(group, table='landmark'):
    """(key, cpp_type, default, min, max, description) of every live-tunable parameter of
    `group` in the table `table` (landmark, tracker, ground, image_input)."""
    found = []
    for line in _lines(table):
        match = _PARAM.match(line)
        if match and match.group(1) == group:
            _, key, _member, cpp_type, default, lo, hi, description = match.groups()
            found.append((key, cpp_type, _value(default, cpp_type), _value(lo, cpp_type) if cpp_type != 'bool' else False,
                          _value(hi, cpp_type) if cpp_type != 'bool' else True, description.replace('\\"', '"')))
    if not found:
        raise RuntimeError('%s_params.def holds no RLE_%s_PARAM entries' % (table, group))
    return found


def settings(node, table):
    """(key, cpp_type, default, min, max, description) of every start-up setting of `node`."""
    found = []
    for line in _lines(table):
        match = _SETTING.match(line)
        if match and match.group(1) == node:
            _, key, cpp_type, default, lo, hi, description = match.groups()
            numeric = cpp_type not in ('bool', 'std::string')
            found.append((key, cpp_type, _value(default, cpp_type), _value(lo, cpp_type) if numeric else None,
                          _value(hi, cpp_type) if numeric else None, description.replace('\\"', '"')))
    return found


def add_group(generator, group, ros_types, table='landmark', edit_methods=None):
    """Adds the parameters of `group` to a ParameterGenerator (or one of its groups). Types:
    bool, double, std::string, and every other one (integers, enums) as int. `edit_methods`:
    key -> an enum made with generator.enum."""
    for key, cpp_type, default, lo, hi, description in entries(group, table):
        extra = {'edit_method': edit_methods[key]} if edit_methods and key in edit_methods else {}
        if cpp_type == 'bool':
            generator.add(key, ros_types['bool'], 0, description, default)
        elif cpp_type == 'std::string':
            generator.add(key, ros_types['str'], 0, description, default)
        else:
            generator.add(key, ros_types['double' if cpp_type == 'double' else 'int'], 0, description,
                          default, lo, hi, **extra)
