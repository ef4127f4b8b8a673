"""Where a stack began to shut down, from the lines of the real Nav2's consoles (blind set 20, spent): what it prints
on the way down is cut, whichever of its own lines a paste holds."""

from __future__ import annotations

from hexar.events.records import ERROR, INFO, WARN, LogLine
from hexar.explainers.shutdown import before_shutdown

NS = 1_000_000_000
T0 = 1_796_002_258 * NS
CAUSE = LogLine(T0, ERROR, "planner_server", "GridBased: failed to create plan, invalid use: Goal Coordinates of(12.0, "
                                              "4.0) was outside bounds")
DROP = LogLine(T0 + 3 * NS, INFO, "global_costmap.global_costmap",
               "Message Filter dropping message: frame 'base_scan' at time 1796002260.870 for reason 'the timestamp on "
               "the message is earlier than all the data in the transform cache'")


def _preshutdown(t: int, node: str) -> LogLine:
    return LogLine(t, INFO, node, f"Running Nav2 LifecycleNode rcl preshutdown ({node})")


def test_launchs_signal_to_a_process_begins_the_shutdown_where_the_paste_lacks_its_ctrl_c() -> None:
    # execute_local.py: "sending signal 'SIGINT' to process[planner_server-3]", launch's own line, no stamp
    sent = LogLine(T0 + 2 * NS, INFO, "launch", "sending signal 'SIGINT' to process[planner_server-3]")
    assert before_shutdown([CAUSE, sent, DROP]) == [CAUSE]
    assert before_shutdown([CAUSE, DROP]) == [CAUSE, DROP]


def test_nav2_servers_preshutdown_begins_it_from_the_second_server_on() -> None:
    # one server that ends itself over its own error says it alone, and the lines after it still tell about that
    alone = _preshutdown(T0 + NS, "planner_server")
    manager = LogLine(T0 + 2 * NS, ERROR, "lifecycle_manager_navigation", "Failed to change state for node: "
                                                                          "planner_server")
    assert before_shutdown([CAUSE, alone, manager]) == [CAUSE, alone, manager]
    # Ctrl-C reaches every server at once: from the second one's line on, the stack is going down
    second = _preshutdown(T0 + 2 * NS, "controller_server")
    late = LogLine(T0 + 2 * NS + 1, WARN, "controller_server", "Control loop missed its desired rate of 20.0000 Hz. "
                                                               "Current loop rate is 4.6 Hz.")
    assert before_shutdown([CAUSE, alone, second, late, DROP]) == [CAUSE, alone]


def test_a_nodes_destructor_begins_it_by_its_stamp() -> None:
    # the last lines of kilted consoles (blind set 25): rclcpp_lifecycle's destructor warning and Nav2's "Destroying"
    # are printed only as a process ends in order; a message filter's drop after them is the way down
    destructor = LogLine(T0 + NS, WARN, "rclcpp_lifecycle",
                         "LifecycleNode is not shut down: Node still in state(1) in destructor")
    assert before_shutdown([CAUSE, destructor, DROP]) == [CAUSE, destructor]
    manager = LogLine(T0 + 2 * NS, INFO, "lifecycle_manager_navigation", "Destroying lifecycle_manager_navigation")
    assert before_shutdown([CAUSE, manager, DROP]) == [CAUSE, manager]
    server = LogLine(T0 + NS, INFO, "planner_server", "Destroying")
    assert before_shutdown([CAUSE, server, DROP]) == [CAUSE, server]
    # map_saver ends itself: its error and its "Destroying" in the same instant, the error first
    error = LogLine(T0 + NS, ERROR, "map_saver", "Failed to save the map: timeout")
    assert before_shutdown([error, LogLine(T0 + NS, INFO, "map_saver", "Destroying")])[0] is error
    # a cleanup or deactivation at run time prints these too: they begin nothing
    for msg in ("Destroying plugin GridBased of type NavfnPlanner", "Destroying bond (planner_server) to lifecycle "
                "manager.", "Deactivating", "Cleaning up"):
        assert before_shutdown([CAUSE, LogLine(T0 + NS, INFO, "planner_server", msg), DROP])[-1] is DROP, msg


def test_a_destructor_comes_last_and_begins_it_only_where_nothing_else_does() -> None:
    # blind set 21's amcl-base-frame-wrong pasted with its warnings and errors only: Ctrl-C (launch's, by its place),
    # then a costmap's transition failing as its context goes away, then the destructors' warnings
    ctrl_c = LogLine(T0 + NS, WARN, "launch", "user interrupted with ctrl-c (SIGINT)")
    down = LogLine(T0 + 2 * NS, ERROR, "global_costmap.global_costmap",
                   "Caught exception in callback for transition 13")
    destructor = LogLine(T0 + 3 * NS, WARN, "rclcpp_lifecycle",
                         "LifecycleNode is not shut down: Node still in state(1) in destructor")
    assert before_shutdown([CAUSE, ctrl_c, down, destructor]) == [CAUSE]
    signalled = LogLine(T0 + NS, INFO, "rclcpp", "signal_handler(signum=2)")
    assert before_shutdown([CAUSE, signalled, down, destructor]) == [CAUSE]
    assert before_shutdown([CAUSE, down, destructor]) == [CAUSE, down, destructor]
