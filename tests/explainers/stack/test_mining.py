"""Reading format strings out of source text: each logging form the mined repositories use, with real message
strings (printf fields, streams, throttled and named macros, exceptions, Python logger calls and raises)."""

from __future__ import annotations

import re

from hexar.explainers.stack.mining import WILD, cpp_calls, literals, py_calls, to_display, to_pattern


def _one(calls: list[object]) -> object:
    assert len(calls) == 1, calls
    return calls[0]


def test_printf_macro_across_lines_skips_the_logger() -> None:
    src = ('void f() {\n  RCLCPP_ERROR(\n    rclcpp::get_logger("nav2_costmap_2d"),\n'
           '    "Transform data too old when converting from %s to %s", a.c_str(), b.c_str());\n}\n')
    [call] = list(cpp_calls(src))
    assert (call.line, call.level, call.form) == (2, "ERROR", "log")
    assert to_display(call.text) == "Transform data too old when converting from … to …"
    assert re.search(to_pattern(call.text), "Transform data too old when converting from odom to map")


def test_a_message_streamed_then_thrown_is_read_from_its_stream() -> None:
    # Fast DDS src/cpp/rtps/attributes/ServerAttributes.cpp:197-199@3.2.x
    src = ('  std::stringstream ss;\n  ss << "Wrong ipv4 address passed into the server\'s list " << address;\n'
           '  throw std::invalid_argument(ss.str());\n  throw std::runtime_error(err.what());\n')
    [call] = list(cpp_calls(src))
    assert (call.line, call.level, call.form) == (3, "ERROR", "throw")
    assert to_display(call.text) == "Wrong ipv4 address passed into the server's list …"


def test_throttled_stream_and_adjacent_literals() -> None:
    src = ('RCLCPP_WARN_THROTTLE(logger_, *clock_, 1000, "Robot is out of bounds " "of the costmap!");\n'
           'RCLCPP_ERROR_STREAM(logger_, "Failed to create controller. Exception: " << ex.what());\n')
    first, second = list(cpp_calls(src))
    assert (first.level, first.text) == ("WARN", "Robot is out of bounds of the costmap!")
    assert second.text == "Failed to create controller. Exception: " + WILD


def test_info_and_debug_are_not_mined_and_exceptions_are() -> None:
    src = ('RCLCPP_INFO(get_logger(), "Begin navigating");\n'
           'throw nav2_core::StartOccupied("Start occupied");\n'
           'RCL_SET_ERROR_MSG_WITH_FORMAT_STRING("Couldn\'t parse params file: \'%s %s\'. Error: %s", a, b, c);\n')
    throw, err = list(cpp_calls(src))
    assert (throw.form, throw.text) == ("throw", "Start occupied")
    assert err.form == "error_msg" and to_display(err.text) == "Couldn't parse params file: '… …'. Error: …"


def test_a_repositorys_own_helpers_are_mined_as_their_level() -> None:
    src = 'if (x) {\n  warn_msg("Aborting handle.");\n  info_msg("Goal accepted");\n}\n'
    [call] = list(cpp_calls(src, {"warn_msg": "WARN", "info_msg": "INFO"}))
    assert (call.line, call.level, call.text) == (2, "WARN", "Aborting handle.")


def test_python_logger_format_and_raise() -> None:
    src = ('        self.__logger.error("process has died [pid {}, exit code {}, cmd \'{}\'].".format(\n'
           "            pid, code, cmd))\n"
           '    raise RuntimeError(f"Invalid frame {frame} given")\n')
    died, raised = list(py_calls(src))
    assert died.level == "ERROR" and to_display(died.text) == "process has died [pid …, exit code …, cmd '…']."
    assert raised.form == "throw" and to_display(raised.text) == "Invalid frame … given"


def test_string_constants_a_log_call_prints_elsewhere() -> None:
    src = 'case X:\n  return "the timestamp on the message is earlier than all the data in the transform cache";\n'
    [(line, text)] = list(literals(src, r'return\s+"([^"]{10,})"'))
    assert line == 2 and text.startswith("the timestamp on the message")


def test_a_python_message_built_in_a_variable_keeps_its_fields_as_wildcards() -> None:
    # launch/launch/launch_service.py:345@humble: the message is formatted into `msg`, then logged
    src = "                    msg = 'Caught exception in launch (see debug for traceback): {}'.format(exc)\n"
    [(line, text)] = list(literals(src, r"msg = '(Caught exception in launch[^']*)'"))
    assert line == 1 and to_pattern(text) == r"Caught exception in launch \(see debug for traceback\):"


def test_patterns_escape_regex_characters_and_keep_spaces() -> None:
    pattern = to_pattern("Sensor origin at (" + WILD + ") is out of map bounds [" + WILD + "]. ")
    assert pattern == r"Sensor origin at \(.*?\) is out of map bounds \[.*?\]\."
    assert re.search(pattern, "Sensor origin at (1.0, 2.0) is out of map bounds [x]. The costmap")


def test_a_field_written_with_an_inttypes_macro_is_a_wildcard() -> None:
    # Cyclone DDS src/core/ddsi/src/ddsi_init.c:1425@releases/11.0.x: "%"PRIu32 between two literals
    src = ('    GVERROR ("rtps_init: failed to create unicast sockets for domain %"PRIu32" participant index %d '
           '(ports %"PRIu32", %"PRIu32")\\n", gv->config.extDomainId.value, idx, port_data_uc, port_disc_uc);\n')
    [call] = list(cpp_calls(src, {"GVERROR": "ERROR"}))
    assert to_display(call.text) == "rtps_init: failed to create unicast sockets for domain … participant index … " \
                                    "(ports …, …)"
    assert re.search(to_pattern(call.text), "rtps_init: failed to create unicast sockets for domain 42 participant "
                                            "index 0 (ports 17910, 17911)")


def test_a_string_constant_cut_by_an_inttypes_macro_ends_in_a_wildcard() -> None:
    # Cyclone DDS src/core/ddsi/src/ddsi_udp.c:505-507@releases/11.0.x: GVLOG with an error category
    src = ('      GVLOG (DDS_LC_CONFIG | DDS_LC_ERROR,\n             "failed to increase socket %s buffer size to at '
           'least %"PRIu32" bytes, current is %"PRIu32" bytes\\n",\n'
           '             name, socket_min_buf_size, actsize);\n')
    [(line, text)] = list(literals(src, r'GVLOG\s*\(\s*[^,"]*DDS_LC_ERROR[^,"]*,\s*"([^"]{10,})"'))
    assert line == 1 and to_display(text) == "failed to increase socket … buffer size to at least …"
    assert re.search(to_pattern(text), "failed to increase socket receive buffer size to at least 67108864 bytes, "
                                       "current is 8388608 bytes")
