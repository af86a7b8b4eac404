"""csrl.run: the same JSON as `csrl run --json`, errors as exceptions, the GIL released,
Ctrl-C honoured."""

import json
import subprocess
import sys

import pytest

import csrl
from csrl import _csrl


def cli_json(cli, *args):
    out = subprocess.run([cli, "run", "--json", *args], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.endswith("\n")
    return out.stdout[:-1]


def cli_error(cli, *args):
    out = subprocess.run([cli, "run", "--json", *args], capture_output=True, text=True)
    assert out.returncode == 1, (out.returncode, out.stderr)
    assert out.stderr.startswith("error: ")
    return out.stderr[len("error: "):].rstrip("\n")


SETTINGS = {
    "temperature": 0.3,
    "max_trials": 400,
    "world": {"slip": 0.1},
    "extensions": {"detector": "action"},
}

CASES = [
    (dict(world="tan3x3", strategy="lazy", seed=1), ["--world", "tan3x3", "--strategy", "lazy", "--seed", "1"]),
    (dict(world="tan8x8", strategy="random", seed=3), ["--world", "tan8x8", "--strategy", "random", "--seed", "3"]),
    (dict(world="frozenlake4x4", strategy="eager", seed=2, trace=True),
     ["--world", "frozenlake4x4", "--strategy", "eager", "--seed", "2", "--trace"]),
    (dict(world="tan3x3", learner="full-sensing", seed=5, max_trials=50),
     ["--world", "tan3x3", "--learner", "full-sensing", "--seed", "5", "--max-trials", "50"]),
    (dict(world="tan3x3", learner="u-tree", seed=4, max_trials=60),
     ["--world", "tan3x3", "--learner", "u-tree", "--seed", "4", "--max-trials", "60"]),
    (dict(), []),
]


def test_arguments_apply_over_the_settings_before_the_check(cli, tmp_path):
    # A [u_tree] table means something only with learner u-tree, given as an argument.
    config = tmp_path / "utree.toml"
    config.write_text("[u_tree]\nfringe = 3\n")
    flags = ["--world", "tan3x3", "--learner", "u-tree", "--seed", "2", "--max-trials", "40", "--config", str(config)]
    expected = cli_json(cli, *flags)
    got = csrl.run_json(world="tan3x3", learner="u-tree", seed=2, max_trials=40, settings={"u_tree": {"fringe": 3}})
    assert got == expected
    with pytest.raises(csrl.SettingsError, match="u_tree"):
        csrl.run(world="tan3x3", settings={"u_tree": {"fringe": 3}})


@pytest.mark.parametrize("kwargs,flags", CASES, ids=lambda c: repr(c)[:60])
def test_run_is_the_cli_byte_for_byte(cli, kwargs, flags):
    expected = cli_json(cli, *flags)
    assert csrl.run_json(**kwargs) == expected
    # The dict written as serde_json writes it gives the same bytes.
    report = csrl.run(**kwargs)
    assert csrl.dumps(report) == expected
    assert report == json.loads(expected)


def test_settings_dict_is_a_config_file(cli, tmp_path):
    config = tmp_path / "beyond.toml"
    config.write_text(_csrl.settings_toml(SETTINGS))
    flags = ["--world", "tan3x3", "--strategy", "lazy", "--seed", "7", "--config", str(config)]
    expected = cli_json(cli, *flags)
    got = csrl.run_json(world="tan3x3", strategy="lazy", seed=7, settings=SETTINGS)
    assert got == expected
    assert csrl.run_json(world="tan3x3", strategy="lazy", seed=7, settings=config) == expected
    # The settings did something: the report differs from the paper's run.
    plain = csrl.run(world="tan3x3", strategy="lazy", seed=7)
    assert plain["settings"]["temperature"] != json.loads(got)["settings"]["temperature"]
    assert json.loads(got)["settings"]["world"]["slip"] == 0.1


def test_seed_changes_the_run():
    a = csrl.run(world="tan8x8", strategy="random", seed=1)
    b = csrl.run(world="tan8x8", strategy="random", seed=2)
    assert a["seed"] == 1 and b["seed"] == 2
    assert (a["trials"], a["total_cost"]) != (b["trials"], b["total_cost"])


def test_world_file_runs_as_the_cli_runs_it(cli, tmp_path):
    path = tmp_path / "lake.json"
    csrl.World("frozenlake4x4", sensing="factors").save(path)
    expected = cli_json(cli, "--world", str(path), "--strategy", "lazy", "--seed", "2")
    assert csrl.run_json(world=str(path), strategy="lazy", seed=2) == expected
    assert csrl.run_json(world=path, strategy="lazy", seed=2) == expected


@pytest.mark.parametrize(
    "kwargs,flags,exc",
    [
        (dict(world="no-such-map"), ["--world", "no-such-map"], csrl.WorldError),
        (dict(world="tan3x3", settings={"temprature": 0.2}), None, csrl.SettingsError),
        (dict(world="tan3x3", settings={"world": {"slide": 0.5}}), None, csrl.SettingsError),
        # A key of [world] at its default, where the world or the learner does not read it.
        (dict(world="tan3x3", settings={"world": {"slide": 0.0}}), None, csrl.SettingsError),
        (dict(world="frozenlake4x4",
              settings={"learner": "belief", "world": {"sensing": "factors", "sensor_noise": 0.0},
                        "costly": {"price": 0.1}}),
         None, csrl.SettingsError),
        (dict(world="tan3x3", learner="u-tree", strategy="lazy"),
         ["--world", "tan3x3", "--learner", "u-tree", "--strategy", "lazy"], csrl.SettingsError),
        (dict(world="tan3x3", settings={"gamma": 1.0}), None, csrl.SettingsError),
        # A key the learner does not read, from the settings or an argument.
        (dict(world="tan3x3", settings={"learner": "belief", "gamma": 0.9, "costly": {"price": 0.1}}),
         None, csrl.SettingsError),
        (dict(world="frozenlake4x4", learner="amrl-q", predict_sensing="off"),
         ["--world", "frozenlake4x4", "--learner", "amrl-q", "--predict-sensing", "off"], csrl.SettingsError),
        # The judging keys moved to [judge].
        (dict(world="tan3x3", settings={"extensions": {"judge_by_quality": True}}), None, csrl.SettingsError),
    ],
)
def test_errors_are_value_errors_with_the_cli_message(cli, tmp_path, kwargs, flags, exc):
    with pytest.raises(exc) as info:
        csrl.run(**kwargs)
    assert isinstance(info.value, ValueError)
    if flags is None:
        # The same settings as a file named "settings", as the Python side names them.
        config = tmp_path / "settings"
        config.write_text(_csrl.settings_toml(kwargs["settings"]))
        flags = ["--world", kwargs["world"], "--config", "settings"]
        out = subprocess.run([cli, "run", "--json", *flags], capture_output=True, text=True, cwd=tmp_path)
        assert out.returncode == 1, out.stderr
        assert str(info.value) == out.stderr[len("error: "):].rstrip("\n")
    else:
        # The command names its flags with their dashes, Python its arguments without.
        assert str(info.value) == cli_error(cli, *flags).replace("--strategy", "strategy")


def test_bad_argument_types_are_refused():
    with pytest.raises(csrl.SettingsError, match="strategy"):
        csrl.run(world="tan3x3", strategy="sometimes")
    with pytest.raises(csrl.SettingsError, match="settings"):
        csrl.run(world="tan3x3", settings={"world": {"slip": object()}})
    with pytest.raises(csrl.SettingsError):
        csrl.run(world="tan3x3", max_trials=0)
    with pytest.raises(csrl.SettingsError):
        csrl.run(world=3.5)


# A child interpreter runs `csrl.run` on its main thread (where Python handles signals)
# while a helper thread waits, in Python, until the main thread is inside the compiled
# run, does some Python work, and sends the process SIGINT. No clock and no fixed wait:
# with the GIL held by the run, the helper could not run at all and the run, which would
# go on for days, would never end; Ctrl-C not honoured, the same. Its ending proves both.
# The child first takes Python's own Ctrl-C handler: a process started in the background
# by a shell inherits SIGINT ignored, and Python then leaves it ignored.
INTERRUPTER = (
    "import os, signal, sys, threading, csrl\n"
    "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
    "main = threading.main_thread().ident\n"
    "def inside_the_run():\n"
    "    f = sys._current_frames().get(main)\n"
    "    while f is not None:\n"
    "        if f.f_code.co_name == 'run' and f.f_code.co_filename.endswith('__init__.py'):\n"
    "            return True\n"
    "        f = f.f_back\n"
    "    return False\n"
    "def helper():\n"
    "    while not inside_the_run():\n"
    "        os.sched_yield()\n"
    "    ticks = sum(i for i in range(100000))\n"
    "    print('ticks', ticks, flush=True)\n"
    "    os.kill(os.getpid(), signal.SIGINT)\n"
    "threading.Thread(target=helper, daemon=True).start()\n"
)


def interrupted(run: str) -> tuple:
    # The timeout guards against a hang only: a run deaf to Ctrl-C goes past it and fails.
    proc = subprocess.run(
        [sys.executable, "-c", INTERRUPTER + run + "\nprint('finished', flush=True)\n"],
        capture_output=True, text=True, timeout=300,
    )
    return proc.returncode, proc.stdout, proc.stderr


def test_the_gil_is_released_during_a_run():
    # The helper thread ran Python code (its ticks) while the run went on.
    code, out, err = interrupted(
        "csrl.run(world='frozenlake8x8', strategy='lazy', seed=1, max_trials=1000000,\n"
        "         settings={'world': {'slip': 0.66}, 'max_moves': 4000000000})"
    )
    assert "ticks 4999950000" in out, (out, err)
    assert "KeyboardInterrupt" in err, err
    assert "finished" not in out
    assert code != 0


def test_ctrl_c_stops_a_long_run():
    code, out, err = interrupted(
        "csrl.run(world='frozenlake8x8', strategy='lazy', seed=1, settings={'world': {'slip': 0.66}, 'max_trials': 1000000})"
    )
    assert "KeyboardInterrupt" in err, err
    assert "finished" not in out
    assert code != 0


def test_ctrl_c_stops_navigation_after_learning():
    # One trial of learning, then navigation that would run for days: 10,000 trials from
    # each state of a policy that learned nothing, with a move cap of four billion.
    code, out, err = interrupted(
        "csrl.run(world='tan8x8', strategy='resetting', seed=1, max_trials=1,\n"
        "         predict_sensing='learned',\n"
        "         settings={'max_moves': 4000000000, 'prediction': {'navigation_trials': 10000}})"
    )
    assert "KeyboardInterrupt" in err, err
    assert "finished" not in out
    assert code != 0


def test_resolve_settings_checks_without_running():
    s = csrl.resolve_settings(world="tan8x8", strategy="eager", settings={"temperature": 0.2})
    assert s["temperature"] == 0.2 and s["strategy"] == "eager"
    with pytest.raises(csrl.SettingsError):
        csrl.resolve_settings(world="tan8x8", settings={"beta": -1.0})


def test_a_built_in_world_named_runs_from_its_own_defaults():
    # Taxi's rewards run from -10 to 20: its temperature, detector and trial cap.
    s = csrl.resolve_settings(world="taxi", strategy="lazy")
    assert (s["temperature"], s["max_trials"], s["extensions"]["detector"]) == (8.0, 200000, "action")
    # A setting given wins, and is echoed.
    s = csrl.resolve_settings(world="taxi", settings={"temperature": 0.4, "extensions": {"detector": "decrease"}})
    assert (s["temperature"], s["extensions"]["detector"]) == (0.4, "decrease")
    report = csrl.run(world="cliffwalking", strategy="eager", seed=1)
    assert report["converged"] and report["policy_quality"] == 1.0
    assert "not_learned" not in report


def test_a_run_that_does_not_learn_says_why():
    report = csrl.run(world="taxi", strategy="lazy", seed=1, max_trials=20, settings={"temperature": 0.4})
    assert not report["converged"]
    assert "No utility ever decreased" in report["not_learned"]["why"]
    assert report["not_learned"]["try"][0] == "temperature = 8"


COSTED = [
    ("belief", {"world": {"sensing": "factors"}, "costly": {"price": 0.025}, "belief": {"trust": 2}}),
    ("belief", {"world": {"sensing": "factors"}, "costly": {"price": 0.025, "rule": "after-outcome"}}),
    ("amrl-q", {"world": {"sensing": "factors"}, "costly": {"price": 0.025}, "amrl_q": {"epsilon": 0.2}}),
]


@pytest.mark.parametrize("learner,settings", COSTED, ids=lambda c: repr(c)[:60])
def test_learners_on_costed_episodes_run_as_the_cli_runs_them(cli, tmp_path, learner, settings):
    config = tmp_path / "costed.toml"
    config.write_text(_csrl.settings_toml(settings))
    flags = ["--world", "frozenlake4x4", "--learner", learner, "--seed", "3", "--episodes", "80",
             "--config", str(config)]
    expected = cli_json(cli, *flags)
    got = csrl.run_json(world="frozenlake4x4", learner=learner, seed=3, episodes=80, settings=settings)
    assert got == expected
    report = csrl.run(world="frozenlake4x4", learner=learner, seed=3, episodes=80, settings=settings)
    assert csrl.dumps(report) == expected
    assert report["learner"] == learner
    assert len(report["costly"]["returns"]) == 80
    assert report["settings"]["costly"]["price"] == 0.025
    # The learner in the settings is the same run.
    inside = dict(settings, learner=learner)
    assert csrl.run_json(world="frozenlake4x4", seed=3, episodes=80, settings=inside) == expected


def test_belief_on_a_world_object():
    lake = csrl.World("frozenlake4x4", sensing="factors")
    report = csrl.run(world=lake, learner="belief", seed=2, episodes=30, settings={"costly": {"price": 0.025}})
    assert report["map"] == "frozenlake4x4" and report["learner"] == "belief"
    assert len(report["costly"]["returns"]) == 30
    # Only the keys the learner reads are echoed.
    assert "gamma" not in report["settings"] and report["settings"]["episodes"] == 30


def test_belief_refusals_are_settings_errors(cli):
    lake = dict(world="frozenlake4x4", learner="belief", episodes=5)
    with pytest.raises(csrl.SettingsError, match="learner = belief"):
        csrl.run(**lake)  # no [costly] price
    with pytest.raises(csrl.SettingsError, match="belief.trust = 0"):
        csrl.run(**lake, settings={"costly": {"price": 0.1}, "belief": {"trust": 0}})
    with pytest.raises(csrl.SettingsError, match=r"\[belief\]"):
        csrl.run(world="frozenlake4x4", settings={"belief": {"trust": 2}})
    with pytest.raises(csrl.SettingsError, match="trace"):
        csrl.run(**lake, settings={"costly": {"price": 0.1}}, trace=True)
    # The same message as the command's.
    config_error = cli_error(cli, "--world", "frozenlake4x4", "--learner", "belief", "--episodes", "5")
    with pytest.raises(csrl.SettingsError) as e:
        csrl.run(**lake)
    assert str(e.value) == config_error


def test_cs_ql_belief_level_runs_as_the_cli_runs_it(cli, tmp_path):
    settings = {"world": {"sensing": "factors", "slide": 0.5}, "costly": {"price": 0.025}, "max_trials": 60}
    config = tmp_path / "level.toml"
    config.write_text(_csrl.settings_toml(settings))
    flags = ["--world", "frozenlake4x4", "--predict-sensing", "weighed", "--seed", "4", "--config", str(config)]
    expected = cli_json(cli, *flags)
    got = csrl.run_json(world="frozenlake4x4", predict_sensing="weighed", seed=4, settings=settings)
    assert got == expected
    report = csrl.run(world="frozenlake4x4", predict_sensing="weighed", seed=4, settings=settings)
    assert report["prediction"]["skipped"] > 0
    assert len(report["costly"]["returns"]) == report["trials"]
    with pytest.raises(csrl.SettingsError, match=r"\[costly\] price"):
        csrl.run(world="tan3x3", predict_sensing="weighed")
