"""``--set NAME=VALUE`` and ``read(path, parameters=...)``: overriding a spec's
``[parameters]`` gives what editing the file would give, on every shipped spec."""

import glob
import json
import os
import sys

import numpy as np
import pytest
from conftest import SHAPES

from plumbob.cli import main
from plumbob.errors import PlumbobError, SpecError
from plumbob.loading import read
from plumbob.spec.loader import build_spec, load_simulation, parse_simulation

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def _toml(path):
    with open(path, "rb") as handle:
        return tomllib.load(handle)


#: every shipped spec with [parameters], and the name of each of its parameters
WITH_PARAMETERS = [
    (os.path.basename(path), name)
    for path in sorted(glob.glob(os.path.join(SHAPES, "*.toml")))
    for name in _toml(path).get("parameters", {})
]


def _edited_value(value):
    """A new value for a parameter: 1.25 times its own (by expression when it is one);
    a parameter that is 0 (a what-if offset such as the sculpture's foot) becomes 0.1."""
    if isinstance(value, (int, float)):
        return 1.25 * value if value else 0.1
    return f"1.25*({value})"


def _numbers(props):
    return np.concatenate([[props.mass], np.ravel(props.center_of_mass), np.ravel(props.inertia)])


def test_every_shipped_spec_with_parameters_is_covered():
    specs = {spec for spec, _ in WITH_PARAMETERS}
    assert len(specs) >= 11 and {"sculpture.toml", "spring_pair.toml"} <= specs


@pytest.mark.parametrize("spec, name", WITH_PARAMETERS)
def test_set_is_the_same_as_editing_the_file(spec, name):
    """The override, against the spec edited in memory (an independent path through
    the reader), and the override must change something the parameter feeds."""
    path = os.path.join(SHAPES, spec)
    data = _toml(path)
    edited = _edited_value(data["parameters"][name])
    data["parameters"][name] = edited
    try:
        expected = build_spec(data, path).body.mass_properties()
    except PlumbobError as error:  # the edit breaks the spec (a rod no longer fits): so must --set
        with pytest.raises(type(error)) as same:
            read(path, parameters={name: str(edited)})
        assert str(same.value) == str(error)
        return
    got = read(path, parameters={name: str(edited)}).body.mass_properties()
    original = read(path).body.mass_properties()
    np.testing.assert_allclose(_numbers(got), _numbers(expected), rtol=1e-12, atol=1e-300)
    if data.get("kind") != "simulation" and "spring" not in data:
        # every parameter of a shape spec shapes the body (a simulation's may only move it)
        assert not np.allclose(_numbers(got), _numbers(original), rtol=1e-9)


@pytest.mark.parametrize("spec", sorted({s for s, _ in WITH_PARAMETERS}))
def test_cli_set_on_every_shipped_spec(spec, capsys):
    path = os.path.join(SHAPES, spec)
    name, value = next(iter(_toml(path)["parameters"].items()))
    edited = _edited_value(value)
    assert main(["mass", path, "--json", "--set", f"{name}={edited}"]) == 0
    out = json.loads(capsys.readouterr().out)
    expected = read(path, parameters={name: edited}).body.mass_properties()
    assert out["mass"] == pytest.approx(expected.mass, rel=1e-15)
    np.testing.assert_allclose(out["center_of_mass"], expected.center_of_mass, rtol=1e-14,
                               atol=1e-15 * np.max(np.abs(expected.center_of_mass)))


def test_later_parameters_follow_an_override():
    """mace_throw: d1 = m2*l/(m1 + m2) follows a new m1."""
    path = os.path.join(SHAPES, "mace_throw.toml")
    spec = load_simulation(path, parameters={"m1": 3})
    positions = spec.model.system.positions
    # d1 + d2 = l, and the centre of mass stays where it was put
    assert np.linalg.norm(positions[0] - positions[1]) == pytest.approx(1.2, rel=1e-14)
    masses = spec.model.system.masses
    assert masses.tolist() == [3.0, 0.5]


def test_override_with_a_length_unit_is_in_the_spec_unit(tmp_path):
    path = tmp_path / "plate.toml"
    path.write_text('[shape]\nunits = "mm"\n[parameters]\nw = 100\n'
                    '[[part]]\ntype = "rectangle"\nwidth = "w"\nheight = 10\n')
    area = read(str(path), parameters={"w": "30 cm"}).body.mass_properties().area
    assert area == pytest.approx(0.3 * 0.01, rel=1e-14)
    assert read(str(path), parameters={"w": "2*10"}).body.mass_properties().area == \
        pytest.approx(0.02 * 0.01, rel=1e-14)


def test_simulation_parameters_through_parse_simulation():
    data = _toml(os.path.join(SHAPES, "spring_pair.toml"))
    spec = parse_simulation(data, "spring_pair.toml", parameters={"m": 3})
    assert spec.model.system.masses.tolist() == [3.0, 3.0]


@pytest.mark.parametrize("overrides, phrases", [
    ({"nope": 1}, ["'nope'", "known: a"]),
    ({"a": "1 furlong"}, ["unknown length unit 'furlong'"]),
    ({"a": "b + 1"}, ["unknown name 'b'"]),
    ({"a": True}, ["expected a number"]),
    ({"a": "1/0"}, ["not a finite number"]),
])
def test_bad_overrides_are_one_line_errors(overrides, phrases):
    with pytest.raises(SpecError) as error:
        read(os.path.join(SHAPES, "l_shape.toml"), parameters=overrides)
    message = str(error.value)
    assert "\n" not in message and "l_shape.toml" in message
    for phrase in phrases:
        assert phrase in message


def test_parameters_for_a_file_that_is_not_a_spec(tmp_path):
    path = tmp_path / "plate.wkt"
    path.write_text("POLYGON ((0 0, 1 0, 1 1, 0 1, 0 0))")
    with pytest.raises(SpecError, match="apply only to a TOML spec"):
        read(str(path), parameters={"a": 1})


def test_spec_without_parameters_says_so(tmp_path):
    path = tmp_path / "plain.toml"
    path.write_text('[[part]]\ntype = "disc"\nradius = 1\n')
    with pytest.raises(SpecError, match=r"known: none \(the spec has no \[parameters\]\)"):
        read(str(path), parameters={"a": 1})


def test_cli_set_errors_are_one_line(capsys):
    path = os.path.join(SHAPES, "l_shape.toml")
    assert main(["mass", path, "--set", "b=2"]) == 2
    assert "known: a" in capsys.readouterr().err
    assert main(["mass", path, "--set", "a=2", "--set", "a=3"]) == 2
    assert "given twice" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stop:
        main(["mass", path, "--set", "a"])
    assert stop.value.code == 2
