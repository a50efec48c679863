"""Scenarios from Python: files and dicts, values set as --set sets them, the plan, and
errors as exceptions with the file:line text."""
import os

import pytest

import regodem
from conftest import SMALL, data_scenario


def test_a_file_validates_into_its_plan():
    plan = regodem.Scenario(SMALL).validate()
    assert [s["name"] for s in plan["stages"]] == ["fill", "press"]
    assert plan["stages"][0]["duration_s"] == pytest.approx(0.3)
    assert plan["stages"][1]["forms_bonds"]
    assert plan["walls"] == ["floor", "cup", "press"]
    assert plan["insertions"] == [{"name": "fill", "count": 40, "stage": "fill"}]
    assert plan["heat"] and plan["time_step_s"] > 0.0
    assert any("time step" in line for line in plan["lines"])
    assert plan["warnings"] == []  # its press moves slowly


def test_values_set_as_the_command_line_sets_them():
    scenario = regodem.Scenario(SMALL).set("stages.fill.duration", "0.2 s").set("insertions.fill.count", 30)
    plan = scenario.validate()
    assert plan["stages"][0]["duration_s"] == pytest.approx(0.2)
    assert plan["insertions"][0]["count"] == 30
    # The same as a list of key=value texts, and as a dict at construction.
    assert regodem.Scenario(SMALL, set=["stages.fill.duration=0.2 s"]).validate()["stages"][0]["duration_s"] == \
        pytest.approx(0.2)
    assert regodem.Scenario(SMALL, set={"stages.fill.duration": "0.2 s"}).validate()["content_hash"] == \
        regodem.Scenario(SMALL, set=["stages.fill.duration=0.2 s"]).validate()["content_hash"]


def test_a_bad_file_raises_input_error_with_its_place():
    path = data_scenario("wrong_unit.yaml")
    with pytest.raises(regodem.InputError) as error:
        regodem.Scenario(path).validate()
    text = str(error.value)
    assert "wrong_unit.yaml:" in text and "radius" in text
    assert isinstance(error.value, ValueError)


def test_a_bad_set_value_names_the_set():
    with pytest.raises(regodem.InputError) as error:
        regodem.Scenario(SMALL).set("stages.fill.duration", "0.2 kg").validate()
    assert "stages.fill.duration" in str(error.value)


def test_an_unknown_key_is_refused():
    with pytest.raises(regodem.InputError) as error:
        regodem.Scenario(data_scenario("unknown_key.yaml")).validate()
    assert "unknown_key.yaml:" in str(error.value)


def test_a_dict_scenario_reads_as_the_file_does():
    data = {
        "name": "from_dict",
        "domain": {"min": ["-5 mm", "-5 mm", 0], "max": ["5 mm", "5 mm", "10 mm"]},
        "materials": {"grain": {"density": "2500 kg/m^3", "shear_modulus": "1e7 Pa", "poisson_ratio": 0.3}},
        "interactions": [{"materials": ["grain", "grain"], "restitution": 0.5, "sliding_friction": 0.5}],
        "walls": [{"name": "floor", "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}],
        "insertions": [{"name": "grains", "material": "grain",
                        "region": {"type": "box", "min": ["-4 mm", "-4 mm", "1 mm"], "max": ["4 mm", "4 mm", "9 mm"]},
                        "radius": "0.5 mm", "count": 20}],
        "stages": [{"name": "settle", "duration": "0.01 s"}],
    }
    plan = regodem.Scenario.from_dict(data, path="virtual/from_dict.yaml").validate()
    assert plan["name"] == "from_dict" and plan["insertions"][0]["count"] == 20
    # The same scenario written by hand as YAML: the same plan, line for line.
    yaml_text = """
name: from_dict
domain: {min: [-5 mm, -5 mm, 0], max: [5 mm, 5 mm, 10 mm]}
materials:
  grain: {density: 2500 kg/m^3, shear_modulus: 1e7 Pa, poisson_ratio: 0.3}
interactions:
  - {materials: [grain, grain], restitution: 0.5, sliding_friction: 0.5}
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1]}
insertions:
  - name: grains
    material: grain
    region: {type: box, min: [-4 mm, -4 mm, 1 mm], max: [4 mm, 4 mm, 9 mm]}
    radius: 0.5 mm
    count: 20
stages:
  - {name: settle, duration: 0.01 s}
"""
    assert regodem.Scenario.from_text(yaml_text, path="virtual/by_hand.yaml").validate()["lines"] == plan["lines"]
    data["insertions"][0]["radius"] = "0.5 kg"
    with pytest.raises(regodem.InputError) as error:
        regodem.Scenario.from_dict(data, path="virtual/from_dict.yaml").validate()
    assert "from_dict.yaml:" in str(error.value) and "radius" in str(error.value)


def test_a_missing_file_is_an_input_error():
    with pytest.raises(regodem.InputError):
        regodem.Scenario(os.path.join("no", "such.yaml")).validate()


def test_text_in_memory_anchors_its_paths_where_its_path_says(tmp_path):
    # A scenario that starts from a bed at out/bed, relative to the scenario's own folder.
    from conftest import SOURCE_DIR, run_cli
    tiny = os.path.join(SOURCE_DIR, "scenarios", "paper", "tiny")
    run_cli("run", os.path.join(tiny, "drill-bed.yaml"), "-o", str(tmp_path / "here" / "out" / "bed"))
    with open(os.path.join(tiny, "drill-heat.yaml")) as f:
        text = f.read()
    plan = regodem.Scenario.from_text(text, path=tmp_path / "here" / "drill.yaml").validate()
    assert plan["particles_at_start"] > 0  # the bed was found beside the path
    # The tiny drill's flutes strike its 1 mm grains faster than 0.2 T_R resolves (9.2
    # steps); at a tenth of the Rayleigh time they get twice as many and no warning.
    assert len(plan["warnings"]) == 1 and "wall 'drill' strikes grains" in plan["warnings"][0]
    assert "warning: " + plan["warnings"][0] in plan["lines"]
    finer = regodem.Scenario.from_text(text, path=tmp_path / "here" / "drill.yaml").set("rayleigh_fraction", 0.1)
    assert finer.validate()["warnings"] == []
    with pytest.raises(regodem.InputError, match="elsewhere.drill.yaml"):
        regodem.Scenario.from_text(text, path=tmp_path / "elsewhere" / "drill.yaml").validate()
    copied = regodem.Scenario(SMALL).copy().set("stages.fill.duration", "0.1 s")
    assert copied.validate()["stages"][0]["duration_s"] == pytest.approx(0.1)
    assert regodem.Scenario(SMALL).validate()["stages"][0]["duration_s"] == pytest.approx(0.3)
