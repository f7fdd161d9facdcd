"""The attributes of the option structs derived from their C++ field lists (Serialize): docstrings
read from the headers' PLATEBALL_FIELD lines and the committed input schema, an eval-able
__repr__, TypeError naming CLASS.FIELD and the value, and Validate() messages from the lists'
ranges."""
import json
import math
import pathlib
import re

import numpy as np
import pytest

import plateball as pb

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Class -> header holding its struct and field list.
HEADERS = {
    "IntegrationOptions": "integration_options.h",
    "IsoparallelOptions": "isoparallel.h",
    "SimulateTask": "problem.h",
    "RigLimits": "rig_limits.h",
    "RigCheckTolerances": "rig_limits.h",
    "FewestImpulsesOptions": "fewest_impulses.h",
    "ExactArrivalOptions": "exact_arrival.h",
    "JoinOptions": "join.h",
    "ReachOptions": "reach.h",
    "PlanOptions": "impulse_planner.h",
    "RigPlanOptions": "rig_planner.h",
}
FIELD = re.compile(r'PLATEBALL_FIELD\(\s*(\w+),\s*((?:"(?:[^"\\]|\\.)*"\s*)+)\)((?:\s*\.\w+\((?:[^()]|\([^()]*\))*\))*)')


def header_fields(cls):
    """[(name, doc, hint)] of the struct's Serialize() list, read from the header's text."""
    text = (ROOT / "include" / "plateball" / HEADERS[cls]).read_text()
    body = text[text.index(f"struct {cls} {{"):]
    body = body[body.index("void Serialize(Archive* a) {"):]
    body = body[:body.index("\n  }\n")]
    fields = []
    for name, literals, chain in FIELD.findall(body):
        doc = "".join(re.findall(r'"((?:[^"\\]|\\.)*)"', literals))
        hint = re.findall(r'"((?:[^"\\]|\\.)*)"', chain)
        fields.append((name, doc, hint[0] if hint else None))
    return fields


def test_every_field_is_a_property_documented_by_its_field_line():
    for cls, header in HEADERS.items():
        fields = header_fields(cls)
        assert len(fields) >= 2, cls
        for name, doc, hint in fields:
            prop = getattr(getattr(pb, cls), name)
            assert isinstance(prop, property), f"{cls}.{name}"
            assert prop.__doc__ == (f"{doc}; {hint}" if hint else doc), f"{cls}.{name}"


def test_docstrings_equal_the_input_schema_descriptions():
    """The problem file's sections are described by the same lists: a file field's docstring is
    the committed schema's description (ByHand fields are described there by hand)."""
    schema = json.loads((ROOT / "schemas" / "input" / "problem.schema.json").read_text())["properties"]
    sections = {"IntegrationOptions": schema["integration"], "SimulateTask": schema["simulate"],
                "IsoparallelOptions": schema["isoparallel"]["properties"]["solver"], "RigLimits": schema["rig"]}
    # The rig's ByHand fields, and its length_unit: a key of the section, not a field of RigLimits.
    by_hand = {"plate", "obstacles", "stroke", "pulse_duration", "length_unit"}
    for cls, section in sections.items():
        compared = 0
        for name, description in ((k, v.get("description")) for k, v in section["properties"].items()):
            if name in by_hand:
                continue
            assert getattr(pb, cls).__dict__[name].__doc__ == description, f"{cls}.{name}"
            compared += 1
        assert compared >= 2, cls


def evaluated(text):
    return eval(text, {**vars(pb), "inf": math.inf, "array": np.array})  # noqa: S307 (our own repr)


def test_repr_lists_every_field_and_round_trips():
    samples = [
        pb.IntegrationOptions(max_steps=17, absolute_tolerance=1e-9),
        pb.IsoparallelOptions(starts=64, seed=7, enumerate_families=False),
        pb.SimulateTask(t_end=2.5, samples=11),
        pb.RigLimits(clearance=0.25, stroke=(1.0, 2.0), tick=0.01),
        pb.FewestImpulsesOptions(max_total_time=12.5, starts=5),
        pb.ExactArrivalOptions(max_iterations=9),
        pb.JoinOptions(local_time_factor=3.0),
        pb.ReachOptions(max_candidates=12),
        pb.PlanOptions(reach_fallback=False, bound_samples=7),
        pb.RigPlanOptions(max_rounds=3, tolerances=pb.RigCheckTolerances(time=1e-10)),
    ]
    for value in samples:
        cls = type(value).__name__
        text = repr(value)
        names = [name for name, _, _ in header_fields(cls)]
        assert text.startswith(cls + "(") and text.endswith(")")
        at = 0
        for name in names:  # every field, in list order (after the nested values before it)
            at = text.index(f"{name}={getattr(value, name)!r}", at)
        again = evaluated(text)
        assert type(again) is type(value) and repr(again) == text, cls
    assert repr(pb.SimulateTask(t_end=2.5, samples=11)) == "SimulateTask(t_end=2.5, samples=11)"
    assert repr(pb.IntegrationOptions()) == (
        "IntegrationOptions(absolute_tolerance=1e-12, relative_tolerance=1e-12, max_steps=2000000)")


def test_wrong_type_names_the_class_the_field_and_the_value():
    cases = [
        (pb.IntegrationOptions(), "max_steps", "x", "int"),
        (pb.IsoparallelOptions(), "length_cap_factor", "2", "float"),
        (pb.SimulateTask(), "samples", 2.5, "int"),
        (pb.RigLimits(), "clearance", None, "float"),
        (pb.FewestImpulsesOptions(), "starts", [1], "int"),
        (pb.ExactArrivalOptions(), "deviation_tolerance", "small", "float"),
        (pb.JoinOptions(), "max_iterations", "x", "int"),
        (pb.PlanOptions(), "reach_fallback", "yes", "bool"),
        (pb.RigPlanOptions(), "max_rounds", 1.5, "int"),
        (pb.RigCheckTolerances(), "time", "0", "float"),
    ]
    for value, field, bad, expected in cases:
        cls = type(value).__name__
        with pytest.raises(TypeError, match=f"^{cls}\\.{field}: value {re.escape(repr(bad))}: must be {expected}$"):
            setattr(value, field, bad)
        with pytest.raises(TypeError, match=f"^{cls}\\(\\): {field}: value {re.escape(repr(bad))}: must be {expected}$"):
            getattr(pb, cls)(**{field: bad})
    with pytest.raises(TypeError, match=r"^IsoparallelOptions\.integration: value 3: must be "
                                        r"plateball\._plateball\.IntegrationOptions$"):
        pb.IsoparallelOptions().integration = 3
    with pytest.raises(TypeError, match=r"^steer\(\): max_iterations: value 'x': must be int$"):
        pb.steer(max_iterations="x")


def test_conversions_and_nested_views_are_as_before():
    """An int is a float field's value, a float is no int field's; a nested value is a view."""
    o = pb.IsoparallelOptions(length_cap_factor=2)
    assert o.length_cap_factor == 2.0 and isinstance(o.length_cap_factor, float)
    o.integration.max_steps = 5
    assert o.integration.max_steps == 5
    plan = pb.PlanOptions()
    plan.join.max_iterations = 3
    assert plan.join.max_iterations == 3
    limits = pb.RigLimits(stroke=np.array([0.5, 0.25]))
    assert list(limits.stroke) == [0.5, 0.25]
    limits.stroke = None
    assert limits.stroke is None


def test_validate_messages_from_the_field_lists():
    """The ranges of the lists, in the messages Validate() gave when it checked them by hand."""
    assert pb.FewestImpulsesOptions(max_total_time=2e6).validate() == (
        "max_total_time: value 2e+06: must be in [0, 1e6] (0: automatic)")
    assert pb.FewestImpulsesOptions(adaptive_starts=-1).validate() == "adaptive_starts: value -1: must be in [0, 10000]"
    assert pb.FewestImpulsesOptions(orientation_tolerance=0.0).validate() == (
        "orientation_tolerance: value 0: must be finite and > 0")
    assert pb.ExactArrivalOptions(max_iterations=51).validate() == "max_iterations: value 51: must be in [1, 50]"
    assert pb.ExactArrivalOptions(deviation_tolerance=math.nan).validate() == (
        "deviation_tolerance: value nan: must be finite and >= 0")
    assert pb.JoinOptions(local_time_factor=0.5).validate() == "local_time_factor: value 0.5: must be in [1, 1000]"
    assert pb.JoinOptions(residual_tolerance=0.01).validate() == "residual_tolerance: value 0.01: must be in [1e-15, 1e-3]"
    assert pb.ReachOptions(scan_directions=4).validate() == "scan_directions: value 4: must be in [8, 100000]"
    assert pb.PlanOptions(bound_samples=1).validate() == "bound_samples: value 1: must be in [2, 100000]"
    assert pb.RigPlanOptions(max_added_points=10001).validate() == (
        "max_added_points: value 10001: must be in [0, 10000]")
    assert pb.RigPlanOptions(tolerances=pb.RigCheckTolerances(impulse=-1.0)).validate() == (
        "tolerances.impulse: value -1: must be finite and >= 0")
    for cls in HEADERS:
        value = getattr(pb, cls)()
        if hasattr(value, "validate"):
            assert value.validate() == "", cls
