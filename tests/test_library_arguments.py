"""Every public function of plumbob checks its arguments (issue 10).

Each bad call below once gave a foreign exception (AttributeError, IndexError,
ValueError, TypeError, MemoryError, OverflowError) or was silently accepted (a
negative ``g``, a NaN datum, a (1, 3) array as one velocity). Each must now raise a
:class:`plumbob.PlumbobError` whose message names the argument.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import plumbob
from plumbob import arguments, primitives
from plumbob.errors import ArgumentError, LimitError, PlumbobError
from plumbob.massprops import MassProperties, point_mass

NAN, INF = math.nan, math.inf


@pytest.fixture(scope="module")
def block():
    return primitives.box(1, 1, 4, density=1000.0)


# (name, call(block), a phrase the message must contain)
FOREIGN = [
    ("load(None)", lambda b: plumbob.load(None), "path"),
    ("load(5)", lambda b: plumbob.load(5), "path"),
    ("load(colour=)", lambda b: plumbob.load("shapes/block.toml", colour="red"), "colour"),
    ("read(NUL in name)", lambda b: plumbob.read("a\0b.stl"), "file name"),
    ("mass_properties(None)", lambda b: plumbob.mass_properties(None), "body"),
    ("mass_properties(5)", lambda b: plumbob.mass_properties(5), "body"),
    ("check(None)", lambda b: plumbob.check(None), "body"),
    ("check(g='a')", lambda b: plumbob.check(b, g="a"), "g"),
    ("check(down='down')", lambda b: plumbob.check(b, down="down"), "down"),
    ("check(props=5)", lambda b: plumbob.check(b, props=5), "props"),
    ("poses(None)", lambda b: plumbob.poses(None), "body"),
    ("lift(None)", lambda b: plumbob.lift(None), "body"),
    ("lift(datum='a')", lambda b: plumbob.lift(b, datum="a"), "datum"),
    ("ParticleSystem(masses='a')", lambda b: plumbob.ParticleSystem(["a"], [[0, 0, 0]]),
     "masses"),
    ("ParticleSystem(velocities (1, 2))",
     lambda b: plumbob.ParticleSystem([1.0], [[0, 0, 0]], velocities=[[0, 0]]), "velocities"),
    ("ParticleSystem(positions ragged)",
     lambda b: plumbob.ParticleSystem([1.0, 2.0], [0, 0, 0]), "position"),
    ("union(block, 5)", lambda b: plumbob.union(b, 5), "not a plumbob body"),
    ("difference(5, block)", lambda b: plumbob.difference(5, b), "not a plumbob body"),
    ("MassProperties(dim=5)",
     lambda b: MassProperties(5, 1.0, 1.0, np.zeros(3), np.eye(3)), "dim"),
    ("MassProperties(centre of 2)",
     lambda b: MassProperties(3, 1.0, 1.0, np.zeros(2), np.eye(3)), "center_of_mass"),
    ("MassProperties(inertia 2x2)",
     lambda b: MassProperties(3, 1.0, 1.0, np.zeros(3), np.eye(2)), "inertia"),
    ("MassProperties + 5", lambda b: b.mass_properties() + 5, "MassProperties"),
    ("MassProperties.translated('a')", lambda b: b.mass_properties().translated("a"), "offset"),
    ("MassProperties.inertia_about((3, 5))",
     lambda b: b.mass_properties().inertia_about(np.zeros((3, 5))), "point"),
    ("box('a')", lambda b: primitives.box("a", 1, 1), "length"),
    ("regular_polygon(1e8 sides)", lambda b: primitives.regular_polygon(10**8, 1), "sides"),
    ("polygon([])", lambda b: primitives.polygon([]), "points"),
    ("polygon(1-D)", lambda b: primitives.polygon([1, 2, 3]), "points"),
    ("pyramid(base 1)", lambda b: primitives.pyramid(1, 1), "base"),
    ("revolve(list)", lambda b: primitives.revolve([[0, 0]]), "profile"),
    ("box.translated('a')", lambda b: b.translated("a"), "offset"),
    # issue 20: numpy's ValueError, an AttributeError, an OverflowError
    ("box.transformed(eye(2))", lambda b: b.transformed(np.eye(2)), "matrix"),
    ("box.transformed(offset of 2)", lambda b: b.transformed(np.eye(3), [1, 2]), "offset"),
    ("disc.transformed(eye(3))", lambda b: primitives.disc(1).transformed(np.eye(3)), "matrix"),
    ("load(units=5)", lambda b: plumbob.load("shapes/block.toml", units=5), "units"),
    ("expr.evaluate(10**400)", lambda b: _evaluate(10**400), "beyond the range"),
    ("expr.evaluate(names=5)", lambda b: _evaluate("a", 5), "names"),
    ("expr.evaluate(names a='x')", lambda b: _evaluate("a", {"a": "x"}), "'a'"),
    ("expr.evaluate(names a=10**400)", lambda b: _evaluate("a", {"a": 10**400}), "'a'"),
]


def _evaluate(*args):
    from plumbob.expr import evaluate

    return evaluate(*args)

def _model(**options):
    from plumbob.dynamics import MotionModel

    pair = plumbob.ParticleSystem([1.0, 2.0], [[0, 0], [1, 0]])
    return MotionModel(pair, **options)


FOREIGN += [
    ("batch.run(None)", lambda b: plumbob.batch.run(None), "inputs"),
    ("batch.run(resume_by='x')",
     lambda b: plumbob.batch.run(["shapes/block.toml"], resume_by="x"), "resume_by"),
    ("MotionModel(None)", lambda b: _model_of(None), "system"),
    ("simulate(method='foo')", lambda b: _simulate(method="foo"), "method"),
]


def _model_of(system):
    from plumbob.dynamics import MotionModel

    return MotionModel(system)


def _simulate(**options):
    from plumbob.dynamics import simulate

    return simulate(_model(), 1.0, **options)


SILENT = [
    ("batch.run('one string')", lambda b: plumbob.batch.run("shapes/block.toml"), "inputs"),
    ("batch.Options(g=-9.81)", lambda b: plumbob.batch.Options(g=-9.81), "g"),
    ("batch.Options(down=0)", lambda b: plumbob.batch.Options(down=(0, 0, 0)), "down"),
    ("batch.Options(require_tilt=100)", lambda b: plumbob.batch.Options(require_tilt=100),
     "require_tilt"),
    ("batch.Options(toward=nan)", lambda b: plumbob.batch.Options(tilt=5, toward=NAN), "toward"),
    ("batch.Options(material='')", lambda b: plumbob.batch.Options(material=""), "material"),
    ("batch.run(jobs=0)", lambda b: plumbob.batch.run(["shapes/block.toml"], jobs=0), "jobs"),
    ("MotionModel(gravity (1, 2))", lambda b: _model(gravity=[[0, -9.81]]), "gravity"),
    ("check(g=-9.81)", lambda b: plumbob.check(b, g=-9.81), "g"),
    ("check(g=0)", lambda b: plumbob.check(b, g=0), "g"),
    ("check(g=nan)", lambda b: plumbob.check(b, g=NAN), "g"),
    ("check(down (1, 3))", lambda b: plumbob.check(b, down=[[0, 0, -1]]), "down"),
    ("check(toward_deg=nan)", lambda b: plumbob.check(b, tilt_deg=5, toward_deg=NAN), "toward"),
    ("check(toward_deg=inf)", lambda b: plumbob.check(b, tilt_deg=5, toward_deg=INF), "toward"),
    ("check(require_tilt_deg=100)", lambda b: plumbob.check(b, require_tilt_deg=100), "90"),
    ("check(require_tilt_deg=-5)", lambda b: plumbob.check(b, require_tilt_deg=-5), "require"),
    ("check(require_tilt_deg=nan)", lambda b: plumbob.check(b, require_tilt_deg=NAN), "require"),
    ("check(g=1e308) overflows", lambda b: plumbob.check(b, g=1e308), "overflows"),
    ("poses(g=1e308) overflows", lambda b: plumbob.poses(b, g=1e308), "overflows"),
    ("poses(g=0)", lambda b: plumbob.poses(b, g=0), "g"),
    ("poses(g=-1)", lambda b: plumbob.poses(b, g=-1), "g"),
    ("poses(sampling_tolerance=-1)", lambda b: plumbob.poses(b, sampling_tolerance=-1),
     "sampling"),
    ("poses(roll_angle_deg=nan)", lambda b: plumbob.poses(b, roll_angle_deg=NAN), "roll"),
    ("lift(datum=nan)", lambda b: plumbob.lift(b, datum=NAN), "datum"),
    ("lift(datum=inf)", lambda b: plumbob.lift(b, datum=INF), "datum"),
    ("lift(g=1e308) overflows", lambda b: plumbob.lift(b, g=1e308), "overflow"),
    ("lift(datum=1e308) overflows", lambda b: plumbob.lift(b, datum=1e308), "overflow"),
    ("lift(up (1, 3))", lambda b: plumbob.lift(b, up=[[0, 0, 1]]), "up"),
    ("collide(v1 (1, 3))", lambda b: plumbob.collide(1, [[1, 0, 0]], 1, [0, 0, 0]), "v1"),
    ("collide(normal (1, 3))",
     lambda b: plumbob.collide(1, [1, 0, 0], 1, [0, 0, 0], normal=[[1, 0, 0]]), "normal"),
    ("collide(1e308 m/s) overflows",
     lambda b: plumbob.collide(1, [1e308, 0, 0], 1, [-1e308, 0, 0]), "double precision"),
    ("ParticleSystem(velocities (1, 1, 3))",
     lambda b: plumbob.ParticleSystem([1.0], [[0, 0, 0]], velocities=[[[0, 0, 0]]]),
     "velocities"),
    ("Assembly((5,))", lambda b: plumbob.Assembly((5,)), "not a plumbob body"),
    ("Lamina(None)", lambda b: plumbob.Lamina(None), "region"),
    ("union(segments=0)", lambda b: plumbob.union(b, b, segments=0), "segments"),
    ("union(segments=2.5)", lambda b: plumbob.union(b, b, segments=2.5), "segments"),
    ("union(segments=1e12)", lambda b: plumbob.union(b, b, segments=10**12), "segments"),
    ("MassProperties(mass=nan)",
     lambda b: MassProperties(3, NAN, 1.0, np.zeros(3), np.eye(3)), "mass"),
    ("MassProperties(inertia ragged)",
     lambda b: MassProperties(3, 1.0, 1.0, np.zeros(3), [[1, 2], [3]]), "inertia"),
    ("MassProperties(inertia None)",
     lambda b: MassProperties(3, 1.0, 1.0, np.zeros(3), None), "inertia"),
    ("MassProperties(mass=-1)",
     lambda b: MassProperties(3, -1.0, 1.0, np.zeros(3), np.eye(3)), "mass"),
    ("MassProperties(centre (1, 3))",
     lambda b: MassProperties(3, 1.0, 1.0, np.zeros((1, 3)), np.eye(3)), "center_of_mass"),
    ("MassProperties.translated([1])", lambda b: b.mass_properties().translated([1]), "offset"),
    ("MassProperties.inertia_about(nan)",
     lambda b: b.mass_properties().inertia_about([NAN, 0, 0]), "point"),
    ("prism(list)", lambda b: primitives.prism([[0, 0], [1, 0]], 1), "profile"),
    ("box.translated(nan)", lambda b: b.translated([NAN, 0, 0]), "offset"),
    ("box.transformed(a stretch)", lambda b: b.transformed(2 * np.eye(3)), "orthogonal"),
    ("box.transformed(nan)", lambda b: b.transformed(np.full((3, 3), NAN)), "matrix"),
    ("box.translated((1, 3))", lambda b: b.translated([[1, 0, 0]]), "offset"),
    ("crew_time(crew=2.5)", lambda b: _crew(2.5), "crew"),
    ("crew_time(work 1e-308) overflows", lambda b: _crew(1, work=1e-308, energy=1e12),
     "overflow"),
]


def _crew(crew, work=1000.0, energy=1e6):
    from plumbob.energy import crew_time

    return crew_time(energy, work, crew)


@pytest.mark.parametrize(("name", "call", "phrase"), FOREIGN + SILENT,
                         ids=[case[0] for case in FOREIGN + SILENT])
def test_a_bad_argument_is_a_plumbob_error_naming_it(block, name, call, phrase):
    with pytest.raises(PlumbobError) as caught:
        call(block)
    assert phrase.lower() in str(caught.value).lower(), str(caught.value)


def test_the_good_calls_next_to_the_bad_ones_still_answer(block):
    """The checks refuse only what is wrong: the closed forms still come out."""
    assert plumbob.check(block, g=1.62).g == 1.62  # the Moon
    lift = plumbob.lift(block, datum=-1.0, g=10.0)
    assert lift.lift_energy == pytest.approx(4000 * 10 * 3.0, rel=1e-15)
    after = plumbob.collide(2.0, 3.0, 1.0)  # scalars are 1-D velocities
    assert after.v1_after[0] == pytest.approx(1.0) and after.v2_after[0] == pytest.approx(4.0)
    one = plumbob.ParticleSystem([2.0], [1.0, 2.0, 3.0], velocities=[0.0, 0.0, 1.0])
    assert one.positions.shape == (1, 3) and one.velocities.shape == (1, 3)
    assert plumbob.poses(block, roll_angle_deg=0.0)[0].probability == pytest.approx(0.2406,
                                                                                   abs=1e-4)


def test_the_lamina_and_solid_checks_keep_their_families(block):
    """A room's errors stay in its family (a StabilityError from check), all PlumbobErrors."""
    from plumbob.errors import DynamicsError, GeometryError, StabilityError

    with pytest.raises(StabilityError):
        plumbob.check(block, g=-1)
    with pytest.raises(DynamicsError):
        plumbob.collide(1, [[1, 0]], 1, [0, 0])
    with pytest.raises(GeometryError):
        primitives.regular_polygon(2, 1)
    with pytest.raises(LimitError):
        primitives.regular_polygon(10**8, 1)


@pytest.mark.parametrize("value", [[[1.0, 0.0, 0.0]], np.zeros((3, 1)), [[1.0], [2.0]], "abc",
                                   None, [1.0, NAN], [INF, 0.0]])
def test_vector_refuses_what_is_not_one_finite_vector(value):
    with pytest.raises(ArgumentError):
        arguments.vector(value, "v", (2, 3))


def test_unit_vector_is_exact_for_huge_components():
    """(1e200, 1e200, 0) overflows a naive norm; the checker scales first."""
    u = arguments.unit_vector([1e200, 1e200, 0.0], "up", (3,))
    assert np.allclose(u, [math.sqrt(0.5), math.sqrt(0.5), 0.0], rtol=0, atol=4e-16)


@pytest.mark.parametrize("value", [True, "x", NAN, INF, -INF, None, [1.0, 2.0]])
def test_number_refuses_what_is_not_a_finite_number(value):
    with pytest.raises(ArgumentError):
        arguments.number(value, "x")


@pytest.mark.parametrize(("value", "ok"), [(3, True), (3.0, True), (2, False), (2.5, False),
                                           (True, False), ("4", False), (NAN, False)])
def test_count_takes_whole_numbers_from_the_minimum(value, ok):
    if ok:
        assert arguments.count(value, "sides", 10, minimum=3) == 3
    else:
        with pytest.raises(ArgumentError):
            arguments.count(value, "sides", 10, minimum=3)


def test_count_over_the_limit_is_a_limit_error_before_the_work():
    with pytest.raises(LimitError, match="over plumbob's limit"):
        arguments.count(10**12, "samples", 10**6)


def test_finite_result_names_the_overflowing_quantity():
    assert arguments.finite_result(np.array([1.0, 2.0]), "x").tolist() == [1.0, 2.0]
    with pytest.raises(ArgumentError, match="the energy overflows"):
        arguments.finite_result([1.0, INF], "the energy")


def test_point_mass_of_one_coordinate_pair_is_a_lamina_point():
    assert point_mass(1.0, [1.0, 2.0]).dim == 2
    with pytest.raises(ArgumentError):
        point_mass(1.0, [1.0])


def _public_callables():
    """Every callable of the public API: ``plumbob.__all__`` and the primitives."""
    found = [(name, getattr(plumbob, name)) for name in plumbob.__all__
             if callable(getattr(plumbob, name)) and name != "PlumbobError"]
    found += [(f"primitives.{name}", getattr(primitives, name)) for name in primitives.__all__]
    return found


def _required(function) -> int:
    import inspect

    params = inspect.signature(function).parameters.values()
    return max(1, sum(p.default is p.empty and p.kind in (p.POSITIONAL_ONLY,
                                                          p.POSITIONAL_OR_KEYWORD)
                      for p in params))


@pytest.mark.parametrize("bad", [None, "x", NAN, [[1.0, 2.0, 3.0]]],
                         ids=["None", "text", "nan", "a (1, 3) array"])
@pytest.mark.parametrize(("name", "function"), _public_callables(),
                         ids=[name for name, _ in _public_callables()])
def test_every_public_callable_refuses_garbage_with_a_plumbob_error(name, function, bad):
    """Enumerated, not listed by hand: a new public function is probed too."""
    with pytest.raises(PlumbobError):
        function(*[bad] * _required(function))


def _bodies():
    """One body of every kind a user builds (the placement methods are probed on each)."""
    cylinder = primitives.cylinder(1, 2)
    return {"mesh": primitives.box(1, 2, 3), "revolution": cylinder,
            "extrusion": primitives.prism(primitives.rectangle(1, 2), 3),
            "lamina": primitives.disc(1),
            "particles": plumbob.ParticleSystem([1.0, 2.0], [[0, 0, 0], [1, 0, 0]]),
            "placed": cylinder.translated([1, 0, 0]),
            "union": plumbob.union(primitives.box(1, 1, 1),
                                   primitives.box(1, 1, 1).translated([0.5, 0, 0]))}


@pytest.mark.parametrize("bad", ["x", NAN, [[1.0, 2.0, 3.0]], "other size", "stretch",
                                 10**400, None])
@pytest.mark.parametrize("kind", list(_bodies()))
def test_every_body_kind_refuses_a_bad_placement_with_a_plumbob_error(kind, bad):
    """``transformed`` and ``translated`` of every kind of body: enumerated, so a new kind
    is probed too (``MeshSolid.transformed(np.eye(2))`` gave numpy's ValueError). None is
    a bad matrix but a good offset (no move)."""
    body = _bodies()[kind]
    bad = {"other size": np.eye(5 - body.dim), "stretch": 2 * np.eye(body.dim)}.get(
        bad, bad) if isinstance(bad, str) else bad
    with pytest.raises(PlumbobError):
        body.transformed(bad)
    if bad is not None and not (np.ndim(bad) == 2 and np.shape(bad)[0] == body.dim):
        with pytest.raises(PlumbobError):
            body.transformed(np.eye(body.dim), bad)
        with pytest.raises(PlumbobError):
            body.translated(bad)


@pytest.mark.parametrize("bad", [None, "x", NAN, [[1.0, 2.0, 3.0]], np.eye(2), 10**400],
                         ids=["None", "text", "nan", "a (1, 3) array", "eye(2)", "10**400"])
@pytest.mark.parametrize("method", ["scaled", "with_density", "mirrored", "translated",
                                    "inertia_about"])
def test_every_mass_properties_method_refuses_garbage_with_a_plumbob_error(block, method, bad):
    """``MassProperties.scaled(None)`` gave a TypeError, ``mirrored('x')`` a ValueError."""
    with pytest.raises(PlumbobError):
        getattr(block.mass_properties(), method)(bad)


def _questions():
    """Every checked question of the Body contract with a good value for each argument
    (the bad ones replace one argument at a time): enumerated from bodies/checked.py's
    table, so a question added there is probed too."""
    from plumbob.bodies.checked import CHECKS
    from plumbob.bodies.graded import with_density_field

    good = {"down": lambda b: [0.0] * (b.dim - 1) + [-1.0], "tolerance": lambda b: 1e-6,
            "points": lambda b: [[0.0] * b.dim], "segments": lambda b: 16,
            "density": lambda b: 1000.0, "thickness": lambda b: None,
            "grader": lambda b: with_density_field(b, "1000")}
    return [(method, list(arguments)) for method, arguments in CHECKS.items()], good


@pytest.mark.parametrize("bad", ["x", NAN, INF, [[1.0, 2.0, 3.0], [1.0]], 10**400, None],
                         ids=["text", "nan", "inf", "ragged", "10**400", "None"])
@pytest.mark.parametrize("kind", list(_bodies()))
def test_every_body_question_refuses_garbage_with_a_plumbob_error(kind, bad):
    """``support_points("x", …)``, ``contains("abc")``, ``graded(None)``,
    ``hull_points(-1)`` gave numpy's ValueError or a NaN-to-integer error. Each argument of
    each question of every kind is given each bad value in turn; the answer is a
    PlumbobError naming the argument, or (None where None is allowed: an optional
    tolerance, no density) a normal answer or a PlumbobError saying the kind cannot answer."""
    body = _bodies()[kind]
    questions, good = _questions()
    for method, names in questions:
        for name in names:
            arguments = {n: good[n](body) if n != "grader" else None for n in names}
            if "grader" in names and name != "grader":
                continue  # the grader's own arguments are with_density_field's to check
            arguments[name] = bad
            try:
                getattr(body, method)(**arguments)
            except PlumbobError as error:
                assert name in str(error) or bad is None, (method, name, str(error))
            else:
                assert bad is None, f"{kind}.{method}({name}={bad!r}) was accepted"
