"""The binding's surface: the stubs (_ldh.pyi) match the native functions' signatures, and
every default the Python API states equals the core's (``_ldh.defaults()``), so a default is
written in one place and a copy cannot drift."""
import ast
import inspect
import pathlib

import pytest

import ldh
from ldh import _ldh

STUB = pathlib.Path(ldh.__file__).with_name("_ldh.pyi")


def _stub_functions():
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    return {f.name: f for f in tree.body if isinstance(f, ast.FunctionDef)}


def _stub_params(f):
    args = f.args.args
    defaults = [None] * (len(args) - len(f.args.defaults)) + list(f.args.defaults)
    return [(a.arg, inspect.Parameter.empty if d is None else ast.literal_eval(d)) for a, d in zip(args, defaults)]


def test_every_native_function_has_a_stub_and_no_stub_is_stale():
    native = {n for n, v in vars(_ldh).items() if callable(v) and not n.startswith("_")}
    assert native == set(_stub_functions()), (native ^ set(_stub_functions()))


@pytest.mark.parametrize("name", sorted(_stub_functions()))
def test_stub_signature_equals_the_binding(name):
    sig = inspect.signature(getattr(_ldh, name))
    native = [(p.name, p.default) for p in sig.parameters.values()]
    assert _stub_params(_stub_functions()[name]) == native


# Python-level functions whose keyword defaults restate the core's (function -> core key).
WRAPPED = {
    ldh.read_recording: "read_recording",
    ldh.analyze: "read_limits",
    ldh.butter_filtfilt: "butter_filtfilt",
    ldh.preprocess: "preprocess",
    ldh.simulate_cohort: "simulate_cohort",
    ldh.lyap_r: "lyap_r",
    ldh.lyap_e: "lyap_e",
    ldh.agree: "agree",
    ldh.reliability: "reliability",
}


@pytest.mark.parametrize("func", list(WRAPPED), ids=lambda f: f.__name__)
def test_python_defaults_equal_the_core_defaults(func):
    core = _ldh.defaults()[WRAPPED[func]]
    sig = inspect.signature(func)
    for name, value in core.items():
        assert name in sig.parameters, (func.__name__, name)
        assert sig.parameters[name].default == value, (func.__name__, name, sig.parameters[name].default, value)


def test_analysis_options_default_to_the_core():
    # ldh.analyze's named options are None ("the core's default"); the core's values are these.
    named = _ldh.defaults()["analyze"]
    # sensor_height_m None: not given, so 0.10 m is assumed and the stride length checked for
    # its dependence on it (``sensor_height_unknown``, docs/quality.md).
    assert named == {"model": "fusion", "detector": "gyro-bracket", "sensor_height_m": None, "compute_sta": True}
    for f in (ldh.analyze, ldh.analyze_pair, ldh.analyze_recording):
        sig = inspect.signature(f)
        for name in named:
            assert sig.parameters[name].default is None, (f.__name__, name)
    full = _ldh.defaults()["analysis_params"]
    assert full["compute_sta"] is True and full["attitude"]["model"] == "fusion"
