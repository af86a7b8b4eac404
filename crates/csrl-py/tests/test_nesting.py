"""Settings and values that contain themselves or nest without end are refused with a
clear exception, never a crash of the interpreter.

Each case runs in a child interpreter: a value walked without a bound overflows the
stack, which would end the test run rather than fail one test.
"""

import subprocess
import sys

import pytest

SETUP = (
    "import csrl\n"
    "def cyclic():\n"
    "    d = {'temperature': 0.2}\n"
    "    d['world'] = d\n"
    "    return d\n"
    "def cyclic_list():\n"
    "    l = [1]\n"
    "    l.append(l)\n"
    "    return {'extensions': {'x': l}}\n"
    "def deep(n=100000):\n"
    "    d = {}\n"
    "    for _ in range(n):\n"
    "        d = {'t': d}\n"
    "    return d\n"
    "def deep_list(n=100000):\n"
    "    l = []\n"
    "    for _ in range(n):\n"
    "        l = [l]\n"
    "    return {'x': l}\n"
)

CALLS = {
    "run": "csrl.run(world='tan3x3', settings={value})",
    "resolve_settings": "csrl.resolve_settings(world='tan3x3', settings={value})",
    "agent": "csrl.CsQlAgent([1.0], [2], 4, settings={value})",
    "dumps": "csrl.dumps({value})",
}

VALUES = {
    "cyclic()": "contains itself",
    "cyclic_list()": "contains itself",
    "deep()": "deeper than",
    "deep_list()": "deeper than",
}


def run_child(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", SETUP + code], capture_output=True, text=True)


@pytest.mark.parametrize("call", sorted(CALLS))
@pytest.mark.parametrize("value", sorted(VALUES))
def test_self_containing_and_deep_values_are_refused(call, value):
    expected = VALUES[value]
    code = (
        "try:\n"
        f"    {CALLS[call].format(value=value)}\n"
        "except csrl.SettingsError as e:\n"
        "    print('refused:', e)\n"
        "else:\n"
        "    print('accepted')\n"
    )
    out = run_child(code)
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    assert out.stdout.startswith("refused:"), out.stdout
    assert expected in out.stdout, out.stdout


def test_the_limits_are_stated_and_a_shallow_value_passes():
    # Nesting up to the limit is fine; one level more is refused, naming the limit.
    code = (
        "print(csrl.dumps(deep(127)) == '{\"t\":' * 127 + '{}' + '}' * 127)\n"
        "try:\n"
        "    csrl.dumps(deep(128))\n"
        "except csrl.SettingsError as e:\n"
        "    print(e)\n"
        "try:\n"
        "    csrl.resolve_settings(settings={'extensions': deep(64)})\n"
        "except csrl.SettingsError as e:\n"
        "    print(e)\n"
        # The same list twice, side by side, is no cycle.
        "shared = [1, 2]\n"
        "print(csrl.dumps({'a': shared, 'b': shared}))\n"
    )
    out = run_child(code)
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    lines = out.stdout.splitlines()
    assert lines[0] == "True"
    assert "deeper than 128 levels" in lines[1], lines[1]
    assert "deeper than 64 levels" in lines[2], lines[2]
    assert lines[3] == '{"a":[1,2],"b":[1,2]}'
