"""The mined stack catalogue: it loads, every pattern compiles, and real lines of each layer read as what they are."""

from __future__ import annotations

import bisect
import functools
import itertools
from pathlib import Path

import pytest

from hexar.explainers.stack.catalogue import (
    LEVELS,
    ROLES,
    Needles,
    StackEntry,
    clean,
    compile_all,
    cut_tail,
    literal_key,
    load,
    stack_catalogue,
)
from hexar.explainers.stack.errors import StackCatalogueError


def test_the_shipped_catalogue_loads_and_every_pattern_compiles() -> None:
    cat = stack_catalogue()
    assert len(cat.entries) > 1000
    assert compile_all(cat.entries) == []
    for e in cat.entries:
        assert e.role in ROLES and e.level in LEVELS, e.source
        assert e.distros and set(e.distros) <= set(cat.distros), e.source
        assert "@" in e.source and ":" in e.source.split("@")[0], e.source
        assert e.cause is None or e.cause.startswith("stack."), e.source


def test_every_stored_key_is_its_patterns_longest_literal_run() -> None:
    # the matcher indexes entries by these keys: a stale one would hide an entry from every message
    raw = stack_catalogue()._raw
    assert all(e["key"] == literal_key(e["pattern"]) for e in raw)


def test_every_layer_the_issue_names_was_mined() -> None:
    layers = stack_catalogue().layers()
    for layer in ("nav2", "rcl", "rclcpp", "lifecycle", "tf", "message_filters", "launch", "robot_localization",
                  "slam_toolbox", "twist_mux", "ros_gz", "rclpy", "middleware", "fastdds", "cyclonedds"):
        assert layers.get(layer, 0) > 0, layer


# Real lines from public threads (turtlebot/turtlebot4#341, #632; ros-navigation/navigation2 corpus threads).
@pytest.mark.parametrize(("msg", "role", "cause", "layer"), [
    ("failed to initialize rcl: Couldn't parse params file: '--params-file /tmp/launch_params_pl1tbamm'. Error: "
     "Cannot have a value before ros__parameters at line 85, at ./src/parse.c:805", "cause", "stack.bringup_failure",
     "rcl"),
    ("Caught exception in callback for transition 10", "cause", "stack.bringup_failure", "lifecycle"),
    ("process has died [pid 6474, exit code -4, cmd '/opt/ros/jazzy/lib/nav2_controller/controller_server "
     "--ros-args']. ", "cause", "stack.bringup_failure", "launch"),
    ("Transform data too old when converting from odom to map", "cause", "stack.transform_error", "nav2"),
    ("Message Filter dropping message: frame 'rplidar_link' at time 1725246931.465 for reason 'the timestamp on "
     "the message is earlier than all the data in the transform cache'", "symptom", "stack.transform_error", "tf"),
    ("RegulatedPurePursuitController detected collision ahead!", "cause", "stack.collision_ahead", "nav2"),
    # ROBOTIS-GIT/turtlebot3#945: launch_service.py:345@humble builds the message in a variable, then logs it
    ("Caught exception in launch (see debug for traceback): while parsing a block mapping\n  in \"/opt/ros/humble/"
     "share/turtlebot3_navigation2/param/waffle.yaml\", line 2, column 3", "cause", "stack.bringup_failure",
     "launch"),
    # nav2_costmap_2d's inflation layer (ERROR): a parameter value it rejects is a configuration error
    ("The configured inflation radius (0.050) is smaller than the computed inscribed radius (0.225) of your "
     "footprint, it is highly recommended to set inflation radius to be at least as big as the inscribed radius to "
     "avoid collisions", "cause", "stack.configuration_error", "nav2"),
    ("GridBased: failed to create plan, no valid path found.", "symptom", None, "nav2"),
    # navfn_planner.cpp@humble: the GOAL off the costmap, not the robot's start
    ("The goal sent to the planner is off the global costmap. Planning will always fail to this goal.", "cause",
     "stack.goal_unreachable", "nav2"),
    # amcl_node.cpp@humble: a parameter AMCL replaces by its default is no localisation fault
    ("You've set max_particles to be negative, this isn't allowed so it will be set to default value 2000.",
     "symptom", None, "nav2"),
    ("[follow_path] [ActionServer] Aborting handle.", "symptom", None, "nav2"),
    ("Failed to make progress", "symptom", None, "nav2"),
    # printed by ROS 2 Kilted here (scripts/runtime_faults.py): a message Fast DDS streams and throws, then logs
    ("[SERVER_CLIENT_DISCOVERY Error] Wrong ipv4 address passed into the server's list 192.168.1.300 -> Function "
     "load_environment_server_info", "cause", "stack.network", "fastdds"),
    # rcl's reason a topic name is not valid, returned as text (validate_topic_name.c) and raised by rclpy
    ("Invalid topic name: topic name must not contain characters other than alphanumerics, '_', '~', '{', or '}':",
     "cause", "stack.configuration_error", "rcl"),
    # rcl_logging_spdlog (a repository of its own), raised by rclpy as it starts a node's logging
    ("failed to initialize logging: Failed to create log directory 'settings.yaml/log': 20, at /project/src/"
     "rcl_logging_spdlog.cpp:153", "cause", "stack.configuration_error", "rcl"),
    # rclpy's lifecycle node (rolling branch: the repository's master stopped when rolling became its default)
    ("Unable to start transition 3 from current state (1, 'unconfigured')", "cause", "stack.bringup_failure",
     "rclpy"),
])
def test_real_lines_read_as_their_role(msg: str, role: str, cause: str | None, layer: str) -> None:
    e = stack_catalogue().match(msg)
    assert e is not None and (e.role, e.cause, e.layer) == (role, cause, layer), e


def test_a_line_no_source_prints_is_not_matched() -> None:
    assert stack_catalogue().match("the coffee machine is out of beans") is None


@pytest.mark.parametrize("text", ["", "[]", '{"distros": []}', '{"distros": [], "mined": [], "entries": [{}]}',
                                  '{"distros": [], "mined": [], "entries": [{"pattern": "x", "text": "x", '
                                  '"level": "LOUD", "form": "log", "layer": "l", "package": "p", "source": "s", '
                                  '"distros": [], "role": "cause"}]}',
                                  # an entry without its text is refused when the file loads, not when a line
                                  # first holds its key
                                  '{"distros": [], "mined": [], "entries": [{"pattern": "x", "level": "WARN", '
                                  '"role": "cause"}]}'])
def test_a_malformed_catalogue_is_a_clear_error(text: str) -> None:
    with pytest.raises(StackCatalogueError, match="malformed stack catalogue"):
        load(text)


# TheWindISeek/tianracer_ros2_ws docs/NAV2_ERRORS_AND_SOLUTIONS.md pastes the inflation layer's ERROR cut after
# "of your footprint" (the rest of the mined message is missing).
CUT = "The configured inflation radius (0.050) is smaller than the computed inscribed radius (0.186) of your footprint"


@pytest.mark.parametrize("tail", ["", "...", " …"])
def test_a_message_pasted_cut_short_reads_as_its_entry(tail: str) -> None:
    e = stack_catalogue().match(CUT + tail)
    assert e is not None and e.cause == "stack.configuration_error"
    assert e.text.startswith("The configured inflation radius (…) is smaller than the computed inscribed radius")


@pytest.mark.parametrize("msg", [
    "The configured inflation radius",  # too little of the message to say which
    "The configured inflation radius (0.050) is smaller than my expectations for this robot",  # another sentence
])
def test_a_few_shared_words_are_no_cut_short_message(msg: str) -> None:
    e = stack_catalogue().match(msg)
    assert e is None or not e.text.startswith("The configured inflation radius")


def test_a_messages_first_sentence_on_a_line_of_its_own_reads_as_its_entry() -> None:
    # MPPI's cost critic (cost_critic.cpp:60-62@jazzy, RCLCPP_WARN) as a console broke it (blind5, spent)
    e = stack_catalogue().match("Inconsistent configuration in collision checking.")
    assert e is not None and e.level == "WARN" and e.package == "nav2_mppi_controller"
    # a sentence that only begins like one, or too short to say which, is not read
    assert stack_catalogue().match("Inconsistent configuration in collision") is None
    assert stack_catalogue().match("Aborting.") is None


def _real_lines() -> list[str]:
    """Every line of every real excerpt HEXAR is evaluated on (the console prefix left on: a matcher must cope)."""
    import yaml

    root = Path(__file__).resolve().parents[3] / "evals" / "data"
    lines: list[str] = []
    for path in sorted([*root.glob("real_nav2/*.yaml"), *root.glob("real_modules/*.yaml")]):
        for excerpt in yaml.load(path.read_text("utf-8"), Loader=yaml.CSafeLoader) or []:
            lines += str(excerpt.get("lines", "")).splitlines()
    return lines


SEP = "\x00"  # in no key and no line: a match in the strings joined by it lies within one of them


def _joined(parts: list[str]) -> tuple[str, list[int]]:
    """The parts joined by SEP, and where each begins (then one past the end)."""
    assert not any(SEP in p for p in parts)
    return SEP.join(parts), list(itertools.accumulate((len(p) + 1 for p in parts), initial=0))


def _keys_in(keys: list[str], texts: list[str]) -> list[list[int]]:
    """For each text, the indices (ascending) of the keys that occur in it: a plain scan of every key, done with
    str.find over all texts joined (no occurrence spans two texts) rather than `key in text` per pair, which took
    a minute on the suites' lines."""
    assert not any(SEP in k for k in keys)
    joined, starts = _joined(texts)
    found: list[list[int]] = [[] for _ in texts]
    for n, key in enumerate(keys):
        if not key:
            for f in found:
                f.append(n)
            continue
        pos = joined.find(key)
        while pos != -1:
            i = bisect.bisect_right(starts, pos) - 1
            found[i].append(n)
            pos = joined.find(key, starts[i + 1])
    return found


@functools.cache
def _real_keys() -> tuple[list[str], list[list[int]]]:
    """The real lines and, per line, the catalogue keys in it (shared: the scan takes seconds)."""
    lines = _real_lines()
    return lines, _keys_in(list(stack_catalogue()._by_key), lines)


def _keys_starting(keys: list[str], prefixes: list[str]) -> list[list[int]]:
    """Per prefix, the indices of the keys that start with it: where the separator before a key is followed by it
    (one more in front of the first key, so that key n's is at its start offset)."""
    assert not any(SEP in p for p in prefixes)
    joined, starts = _joined(keys)
    joined = SEP + joined
    found: list[list[int]] = []
    for prefix in prefixes:
        found.append([])
        pos = joined.find(SEP + prefix)
        while pos != -1:
            found[-1].append(bisect.bisect_left(starts, pos))
            pos = joined.find(SEP + prefix, pos + 1)
    return found


def test_the_plain_scans_find_what_in_and_startswith_find() -> None:
    keys = ["", "a", "ab", "b a", "ERROR", "[ERROR] [", "rror", "x" * 3]
    texts = ["", "a", "ab", "bab a", "[ERROR] [amcl]: rror", "xx", "xxx", "ERROR", "abab"]
    assert _keys_in(keys, texts) == [[n for n, k in enumerate(keys) if k in t] for t in texts]
    prefixes = ["", "a", "ab", "b", "x", "xxxx", "ERROR", "[", "c"]
    assert _keys_starting(keys, prefixes) == [[n for n, k in enumerate(keys) if k.startswith(p)] for p in prefixes]


def test_the_key_index_finds_exactly_the_keys_a_plain_scan_finds() -> None:
    cat = stack_catalogue()
    needles = Needles(cat._by_key)
    real, real_keys = _real_keys()
    extra = [e.text for e in cat.entries[::7]] + ["", "a", "abc", "[ERROR]", "x" * 500]
    texts = real + extra
    assert len(texts) > 2000 and needles.needles == list(cat._by_key)
    for text, keys in zip(texts, real_keys + _keys_in(needles.needles, extra), strict=True):
        assert needles.found_in(text) == keys, text
    short = Needles(["", "a", "Er", "ERR", "ERROR", "[ERROR] [", "costmap", "rror"])
    for text in texts[::5]:
        assert short.found_in(text) == [n for n, key in enumerate(short.needles) if key in text], text
    prefixes = [text[:40] for text in texts[::10]]
    for prefix, keys in zip(prefixes, _keys_starting(needles.needles, prefixes), strict=True):
        assert needles.starting_with(prefix) == keys, prefix


def test_every_real_line_reads_as_a_plain_scan_of_every_key_reads_it() -> None:
    cat = stack_catalogue()
    by_key = list(cat._by_key.items())

    def plain_best(text: str, present: list[int]) -> StackEntry | None:
        best = None
        for key in present:
            for i in by_key[key][1]:
                e = cat._at(i)
                if (best is None or (e.cause is not None, e.specificity) > (best.cause is not None, best.specificity)
                        ) and e.regex.search(text):
                    best = e
        return best

    lines, keys = _real_keys()
    named = 0
    for line, present in zip(lines, keys, strict=True):
        text = clean(line)
        if text != line:
            present = _keys_in([k for k, _ in by_key], [text])[0]
        best = cat._best(text)
        assert best is plain_best(text, present), line
        named += best is not None
    assert named > 300


def test_a_cut_tail_is_the_longest_start_of_the_piece_the_text_ends_with() -> None:
    import numpy as np

    def every_length(rest: str, piece: str, least: int) -> int:
        return next((j for j in range(len(piece) - 1, least - 1, -1) if rest.endswith(piece[:j])), 0)

    rng = np.random.default_rng(5)
    pieces = [p for e in stack_catalogue().entries[::25] for p in e.pieces if p]
    for _ in range(3000):
        piece = pieces[int(rng.integers(len(pieces)))]
        cut = int(rng.integers(len(piece) + 1))
        rest = "".join(rng.choice(list("ab ["), int(rng.integers(6)))) + piece[:cut]
        if rng.random() < 0.3:
            rest = rest + piece[: int(rng.integers(len(piece) + 1))]  # the start twice: the longer one counts
        least = int(rng.integers(1, 12))
        assert cut_tail(rest, piece, least) == every_length(rest, piece, least), (rest, piece, least)
