"""What rclpy's action layer says happened to a goal, whatever the program around it logs (stable API).

    action_finding(lines) -> ActionFinding | None
    action_words(finding, head) -> (sentence, fix) | None

rclpy's action server and client (rclpy/action/server.py and client.py, mined into the stack catalogue) log a few
lines of their own that tell what became of a goal:
- "Ignoring unexpected goal|cancel|result response. There may be more than one action server for the action '…'"
  (client.py:314-334@rolling): an answer came for a request the client had already had answered: a second server
  runs under the same action name, and both may execute the goal.
- "Goal state not set, assuming aborted. Goal ID: …" (server.py:351@rolling): the server's execute callback returned
  without ending the goal (succeed(), abort() or canceled()), so rclpy aborted it: the server's own code ended it.
- "Sending result response for unknown or expired goal ID: …" (server.py:416@rolling): the client asked for the
  result of a goal the server does not keep: one it never accepted, or one whose result it dropped after its
  result_timeout. An error of the server's own node before it is the reason it refused the goal; without one, the
  lines do not tell which of the two it was.
rclpy logs these under the node's child loggers (`<node>.action_server`, `<node>.action_client`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from hexar.events.records import ERROR, LogLine

_TWO_SERVERS = re.compile(r"Ignoring unexpected (goal|cancel|result) response\. There may be more than one action "
                          r"server for the action '(?P<action>[^']*)'")
_NOT_ENDED = "Goal state not set, assuming aborted"
_UNKNOWN_GOAL = "Sending result response for unknown or expired goal ID"
_SERVER = ".action_server"

Kind = Literal["two_servers", "not_ended", "refused", "unknown_goal"]


@dataclass(frozen=True)
class ActionFinding:
    kind: Kind
    line: LogLine  # rclpy's own line
    server: str = ""  # the server's node, where the line is the server's
    action: str = ""  # the action's name, where the line gives it
    reason: LogLine | None = None  # the server node's own error before a goal it did not keep (refused)


# A refusal answers the goal request, and a client that goes on asks for the result as soon as it has the answer: an
# error of the server's node older than this is about something else.
_REFUSAL_S = 2.0


def _server_error(lines: Sequence[LogLine], server: str, before: LogLine) -> LogLine | None:
    """The server node's own last error shortly before `before` (its child loggers are rclpy's, not the node's
    code)."""
    since = before.t - int(_REFUSAL_S * 1e9)
    return next((ln for ln in reversed(lines) if since <= ln.t <= before.t and ln is not before
                 and ln.level >= ERROR and ln.name.strip("/") == server), None)


def action_finding(lines: Sequence[LogLine]) -> ActionFinding | None:
    """The first of rclpy's action-layer lines above, with what it tells; None when there is none."""
    for line in lines:
        if (m := _TWO_SERVERS.search(line.msg)) is not None:
            return ActionFinding("two_servers", line, action=m["action"])
        name = line.name.strip("/")
        if not name.endswith(_SERVER):
            continue
        server = name.removesuffix(_SERVER)
        if line.msg.startswith(_NOT_ENDED):
            return ActionFinding("not_ended", line, server)
        if line.msg.startswith(_UNKNOWN_GOAL):
            reason = _server_error(lines, server, line)
            return ActionFinding("refused" if reason is not None else "unknown_goal", line, server, reason=reason)
    return None


def action_words(finding: ActionFinding, head: str) -> tuple[str, str] | None:
    """(sentence, fix) for a finding that tells a cause, `head` being "<what> failed because": two_servers a set-up
    mistake; not_ended and refused the arm's execution failing (manipulation.execution_failed's words). None for a
    goal the server did not keep where no error of its own says it refused it: the lines leave that open."""
    from hexar.explainers.logcause import said

    if finding.kind == "two_servers":
        return (f"{head} two action servers answer to the same action name ({finding.action or 'one action'}), so "
                "a goal sent to it can be executed twice and the client ignores the second server's answers.",
                "Run one server per action name: rename or remove the second node that serves it (a test or "
                "simulated controller left running beside the real one is common).")
    if finding.kind == "not_ended":
        return (f"{head} the execution of my arm trajectory failed: the controller's action server "
                f"({finding.server}) ended the goal without a result (its execute callback returned without "
                "succeeding or aborting it), so rclpy aborted it.",
                f"Fix {finding.server}'s execute callback so that every way out of it ends the goal "
                "(goal_handle.succeed(), abort() or canceled()) and returns a result.")
    if finding.kind == "refused" and finding.reason is not None:
        return (f"{head} the execution of my arm trajectory failed: the controller ({finding.server}) did not take "
                f"the goal, saying '{said(finding.reason)}', and was then asked for the result of a goal it did "
                "not have.",
                "Send a goal the controller takes (what its error names), and check that a goal was accepted "
                "before waiting for its result.")
    return None
