"""Scenarios: a file or a dict, with values changed as `--set` changes them."""
import json
import os

from . import _regodem


def _yaml_value(value):
    """A Python value as the YAML text --set takes: strings as they are ("20 mm"), the
    rest as JSON, which is YAML (numbers, lists, dicts, true/false, null)."""
    if isinstance(value, str):
        return value
    return json.dumps(value)


class Scenario:
    """A scenario file, or a dict, and the values set on it.

    Scenario(path, set=None): a YAML file; `set` a dict {"key.path": value} or a list
    of "key.path=value" texts, applied in order as `regodem run --set` applies them.
    Scenario.from_dict(d, path="scenario.yaml"): a scenario as a dict; `path` names it
    in messages and anchors its relative paths (meshes, particle files).
    """

    def __init__(self, path, set=None):
        self.path = os.fspath(path)
        self.text = None
        self.overrides = []
        self._add(set)

    @classmethod
    def from_dict(cls, data, path="scenario.yaml"):
        scenario = cls.__new__(cls)
        scenario.path = os.fspath(path)
        scenario.text = json.dumps(data, indent=1)
        scenario.overrides = []
        return scenario

    @classmethod
    def from_text(cls, text, path="scenario.yaml"):
        scenario = cls.__new__(cls)
        scenario.path = os.fspath(path)
        scenario.text = str(text)
        scenario.overrides = []
        return scenario

    def _add(self, values):
        if values is None:
            return
        if isinstance(values, dict):
            for key, value in values.items():
                self.set(key, value)
        else:
            for text in values:
                if "=" not in text:
                    raise InputError(f"--set value '{text}' is not key.path=value")
                self.overrides.append(text)

    def set(self, key, value):
        """Sets one value as `--set key=value` does (a unit string such as "20 mm", a
        number, a list); returns the scenario, so calls chain. Checked by validate()."""
        self.overrides.append(f"{key}={_yaml_value(value)}")
        return self

    def copy(self):
        other = Scenario.__new__(Scenario)
        other.path, other.text, other.overrides = self.path, self.text, list(self.overrides)
        return other

    def validate(self):
        """Reads and builds the scenario as `regodem validate` does and returns its plan:
        a dict with `lines` (what validate prints), `time_step_s`, `stages`, `walls`,
        `insertions`, ... Raises InputError naming every problem with its file:line."""
        return _regodem.validate(self.path, self.text, self.overrides)

    def plan(self):
        """The same as validate()."""
        return self.validate()

    def __repr__(self):
        source = "dict" if self.text is not None else "file"
        return f"Scenario({self.path!r}, {source}, {len(self.overrides)} values set)"


InputError = _regodem.InputError
