"""Bad interface spec files (TOML) for ``read_interfaces`` (``flexpipe reduce --interfaces``).

Every bad entry is placed first, second and third among valid ones, so each error must
name the right table.
"""

from __future__ import annotations

GOOD = ['name = "a"\npoint = [0.0, 0.0, 0.0]\nradius = 0.05',
        'name = "b"\npoint = [1.0, 0.0, 0.0]\nnodes = [1, 2, 3]',
        'name = "c"\npoint = [2.0, 0.0, 0.0]\nnode_set = "tow"']

BAD_ENTRIES = {
    "typo-key": 'name = "x"\npoint = [0, 1, 0]\nraduis = 0.1',
    "name-number": 'name = 5\npoint = [0, 1, 0]\nradius = 0.1',
    "name-empty": 'name = ""\npoint = [0, 1, 0]\nradius = 0.1',
    "name-blank": 'name = "   "\npoint = [0, 1, 0]\nradius = 0.1',
    "name-duplicate": 'name = "a"\npoint = [0, 1, 0]\nradius = 0.1',
    "point-missing": 'name = "x"\nradius = 0.1',
    "point-two": 'name = "x"\npoint = [0, 1]\nradius = 0.1',
    "point-four": 'name = "x"\npoint = [0, 1, 2, 3]\nradius = 0.1',
    "point-text": 'name = "x"\npoint = ["a", 0, 0]\nradius = 0.1',
    "point-nan": 'name = "x"\npoint = [nan, 0, 0]\nradius = 0.1',
    "point-inf": 'name = "x"\npoint = [0, inf, 0]\nradius = 0.1',
    "point-bool": 'name = "x"\npoint = [true, 0, 0]\nradius = 0.1',
    "point-string": 'name = "x"\npoint = "0, 1, 0"\nradius = 0.1',
    "point-nested": 'name = "x"\npoint = [[0, 1, 0]]\nradius = 0.1',
    "point-table": 'name = "x"\npoint = {x = 0, y = 1, z = 0}\nradius = 0.1',
    "radius-zero": 'name = "x"\npoint = [0, 1, 0]\nradius = 0',
    "radius-negative": 'name = "x"\npoint = [0, 1, 0]\nradius = -0.1',
    "radius-text": 'name = "x"\npoint = [0, 1, 0]\nradius = "0.1"',
    "radius-nan": 'name = "x"\npoint = [0, 1, 0]\nradius = nan',
    "radius-inf": 'name = "x"\npoint = [0, 1, 0]\nradius = inf',
    "radius-bool": 'name = "x"\npoint = [0, 1, 0]\nradius = true',
    "radius-list": 'name = "x"\npoint = [0, 1, 0]\nradius = [0.1]',
    "nodes-text": 'name = "x"\npoint = [0, 1, 0]\nnodes = ["a"]',
    "nodes-float": 'name = "x"\npoint = [0, 1, 0]\nnodes = [4.7]',
    "nodes-integral-float": 'name = "x"\npoint = [0, 1, 0]\nnodes = [4.0]',
    "nodes-empty": 'name = "x"\npoint = [0, 1, 0]\nnodes = []',
    "nodes-negative": 'name = "x"\npoint = [0, 1, 0]\nnodes = [-1]',
    "nodes-string": 'name = "x"\npoint = [0, 1, 0]\nnodes = "1, 2"',
    "nodes-nested": 'name = "x"\npoint = [0, 1, 0]\nnodes = [[1, 2]]',
    "nodes-bool": 'name = "x"\npoint = [0, 1, 0]\nnodes = [true]',
    "nodes-scalar": 'name = "x"\npoint = [0, 1, 0]\nnodes = 4',
    "radius-and-nodes": 'name = "x"\npoint = [0, 1, 0]\nradius = 0.1\nnodes = [1, 2]',
    "radius-and-set": 'name = "x"\npoint = [0, 1, 0]\nradius = 0.1\nnode_set = "s"',
    "nodes-and-set": 'name = "x"\npoint = [0, 1, 0]\nnodes = [1]\nnode_set = "s"',
    "set-number": 'name = "x"\npoint = [0, 1, 0]\nnode_set = 5',
    "set-empty": 'name = "x"\npoint = [0, 1, 0]\nnode_set = ""',
    "dofs-four": 'name = "x"\npoint = [0, 1, 0]\nradius = 0.1\ndofs = 4',
    "dofs-text": 'name = "x"\npoint = [0, 1, 0]\nradius = 0.1\ndofs = "6"',
    "dofs-bool": 'name = "x"\npoint = [0, 1, 0]\nradius = 0.1\ndofs = true',
    "dofs-float": 'name = "x"\npoint = [0, 1, 0]\nradius = 0.1\ndofs = 6.5',
}

WHOLE = {
    "empty": (b"", "error"),
    "comment-only": (b"# nothing here\n", "error"),
    "latin1": ('[[interface]]\nname = "caf\xe9"\npoint = [0, 0, 0]\nradius = 0.1\n'
               .encode("latin-1"), "error"),
    "utf16": ('[[interface]]\nname = "a"\npoint = [0, 0, 0]\nradius = 0.1\n'
              .encode("utf-16"), "error"),
    "binary": (bytes(range(256)) * 4, "error"),
    "zeros": (b"\x00" * 100, "error:file"),
    "unclosed-bracket": (b'[[interface]\nname = "a"\n', "error"),
    "missing-value": (b'[[interface]]\nname =\n', "error"),
    "duplicate-key": (b'[[interface]]\nname = "a"\nname = "b"\npoint = [0,0,0]\n', "error"),
    "bad-escape": (b'[[interface]]\nname = "a\\q"\npoint = [0,0,0]\n', "error"),
    "unterminated-string": (b'[[interface]]\nname = "a\npoint = [0,0,0]\n', "error"),
    "deep-nesting": (b"a = " + b"[" * 5000 + b"]" * 5000 + b"\n", "error"),
    "deep-inline-tables": (b"a = " + b"{b = " * 3000 + b"1" + b"}" * 3000 + b"\n", "error"),
    "interface-list-of-ints": (b"interface = [1, 2]\n", "error"),
    "interface-string": (b'interface = "left"\n', "error"),
    "interface-single-table": (b'[interface]\nname = "a"\npoint = [0,0,0]\nradius = 0.1\n',
                               "error"),
    "interface-empty-list": (b"interface = []\n", "error"),
    "interface-mixed-list": (b'interface = [{name = "a", point = [0,0,0], radius = 0.1}, 3]\n',
                             "error"),
    "unknown-top-level": (b'radious = 0.1\n[[interface]]\nname = "a"\npoint = [0,0,0]\n',
                          "error"),
    "top-radius-negative": (b'radius = -1\n[[interface]]\nname = "a"\npoint = [0,0,0]\n',
                            "error"),
    "top-radius-text": (b'radius = "big"\n[[interface]]\nname = "a"\npoint = [0,0,0]\n',
                        "error"),
    "top-radius-bool": (b'radius = true\n[[interface]]\nname = "a"\npoint = [0,0,0]\n',
                        "error"),
    "top-radius-nan": (b'radius = nan\n[[interface]]\nname = "a"\npoint = [0,0,0]\n', "error"),
    "top-radius-zero": (b'radius = 0.0\n[[interface]]\nname = "a"\npoint = [0,0,0]\n',
                        "error"),
}

OK = {
    "three-kinds": "\n\n".join("[[interface]]\n" + g for g in GOOD),
    "default-radius": 'radius = 0.1\n[[interface]]\nname = "a"\npoint = [0, 0, 0]\n'
                      '[[interface]]\nname = "b"\npoint = [1, 0, 0]\n',
    "default-radius-with-nodes": 'radius = 0.1\n[[interface]]\npoint = [0, 0, 0]\n'
                                 'nodes = [4, 5]\n',
    "node-at-point": '[[interface]]\nname = "n"\npoint = [0, 0, 0]\n',
    "unnamed": '[[interface]]\npoint = [0, 0, 0]\nradius = 0.2\n',
    "inline-array": 'interface = [{name = "a", point = [0, 0, 0], radius = 0.1}]\n',
    "comments-and-blank-lines": '# spec\n\n[[interface]]  # first\nname = "a"  # name\n'
                                'point = [0.0, 0.0, 0.0]\n\nradius = 0.05\n',
    "integers-as-coordinates": '[[interface]]\nname = "a"\npoint = [0, 1, 2]\nradius = 1\n',
    "unicode-name": '[[interface]]\nname = "Federbeinstütze"\npoint = [0, 0, 0]\n'
                    'radius = 0.1\n',
    "three-dofs": '[[interface]]\nname = "a"\npoint = [0, 0, 0]\nradius = 0.1\ndofs = 3\n',
    "crlf": '[[interface]]\r\nname = "a"\r\npoint = [0, 0, 0]\r\nradius = 0.1\r\n',
}


def cases():
    for name, text in OK.items():
        yield f"ok-{name}", "interfaces.toml", text.encode(), "ok"
    for name, (data, expect) in WHOLE.items():
        yield f"file-{name}", "interfaces.toml", data, expect
    for name, entry in BAD_ENTRIES.items():
        for pos in range(3):
            entries = list(GOOD)
            entries.insert(pos, entry)
            text = "# interface spec\nradius = 0.08\n\n" if name.startswith("radius-and") \
                else "# interface spec\n\n"
            text += "\n\n".join("[[interface]]\n" + e for e in entries) + "\n"
            yield f"{name}-at-{pos + 1}", "interfaces.toml", text.encode(), "error"
