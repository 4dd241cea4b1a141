# SPDX-License-Identifier: MIT
"""The package's surface: stubs that match the module, enums that match the
stubs' values, docstrings on everything public."""
import ast
import os

import smartcollision as sc
import smartcollision._core as core

STUBS = os.path.join(os.path.dirname(sc.__file__), "_core.pyi")


def stub_tree():
    with open(STUBS) as f:
        return ast.parse(f.read())


def public(names):
    return {n for n in names if not n.startswith("_")}


def test_stubs_name_every_public_symbol():
    tree = stub_tree()
    declared = {node.name for node in tree.body if isinstance(node, ast.ClassDef)}
    declared |= {t.id for node in tree.body if isinstance(node, ast.AnnAssign) for t in [node.target]}
    aliases = {"ArrayLike", "FloatArray", "IntArray", "Pose", "ContactArrays"}
    assert public(dir(core)) == declared - aliases


def test_stub_classes_match_members():
    for node in stub_tree().body:
        if not isinstance(node, ast.ClassDef) or issubclass(getattr(core, node.name), BaseException):
            continue
        cls = getattr(core, node.name)
        members = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        members |= {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
        members |= {t.id for n in node.body if isinstance(n, ast.Assign) for t in n.targets}
        runtime = public(vars(cls)) - {"name", "value"}
        if hasattr(cls, "__members__"):                    # enums: values are checked below
            runtime = public(cls.__members__)
            for n in node.body:
                if isinstance(n, ast.Assign):
                    assert int(getattr(cls, n.targets[0].id)) == n.value.value, (node.name, n.targets[0].id)
        assert public(members) - {"__init__", "__len__"} == runtime, node.name


def test_docstrings():
    assert "penetration depth" in sc.__doc__
    for name in ("Model", "PairTracker", "Scene", "Result", "Settings"):
        assert len(getattr(sc, name).__doc__) > 40, name
    for name in ("distance", "penetration", "update", "contacts"):
        assert getattr(sc.PairTracker, name).__doc__.count("\n") >= 1, name
    assert sc.PairTracker.__module__ == "smartcollision"
    assert "smartcollision.Model" in sc.PairTracker.__init__.__doc__
