"""What kind of turn a question is: a new question, or a follow-up on the last answer.

Written for transcribed speech too: lower case, no punctuation, small misrecognitions.
"""

from __future__ import annotations

import re

from hexar.agent.all_up import all_up_kind
from hexar.agent.attempts import TRIED
from hexar.agent.between import between_asked, spans_two
from hexar.agent.counted import count_asked
from hexar.agent.flags import BATTERY, LIMIT, flag_asked
from hexar.agent.goal_sent import goal_sent_kind
from hexar.agent.health import health_kind
from hexar.agent.logs import LOGS, NODES
from hexar.agent.matters import asks_matters
from hexar.agent.means import means_asked
from hexar.agent.measure_words import measure_kind
from hexar.agent.mentions import mentions_kind
from hexar.agent.node_status import node_status_kind
from hexar.agent.overview import SETTING_FIX
from hexar.agent.person import PERSON
from hexar.agent.places import AT_PLACE, FAILED_AT, GOAL, REACHED, ROUTE, place_asked
from hexar.agent.plugins import PLUGINS
from hexar.agent.recording import clock_kind
from hexar.agent.sequence import AFTER, DOING, PLAN, REQUEST, TASKS
from hexar.agent.skills import ABLE, SKILLS
from hexar.agent.state import Intent
from hexar.agent.step_status import step_asked
from hexar.agent.unnamed import unnamed_kind
from hexar.agent.unseen import unseen_kind
from hexar.agent.window import window_kind

_DEEPER = re.compile(
    r"^(and |but |so |ok |okay )?(why( is| was| did)?( that| this| it)?( so| happen(ed)?)?|why not|how come|"
    r"how do you know( that)?|"
    r"tell me more|more details?|go on|explain( that| more)?|what do you mean|because of what)\W*$"
)
_HELPED = re.compile(
    SETTING_FIX + "|"
    r"what (would|could|might) have (helped|worked|prevented it|made a difference)|"
    r"what (could|can|should) (i|we|you) (have )?do(ne)?( differently| about it)?|how (can|could|do) (i|we) fix|"
    r"how (can|could) (i|we|you) (avoid|prevent)|"
    r"what (should|do|can|must) (i|we) (need to |have to )?(do|change|check|look at|look into|fix)\b|"
    r"how do i fix|"
    r"what (would|do|should) you (recommend|suggest) (i|we) (do|change)"
)
# "what else could you have picked?" asks for another choice (the counterfactual), not for more findings
_CHOICE = r"(pick|picked|choose|chosen|recommend|recommended|suggest|suggested|offer|offered|go with|gone with)"
_ELSE = re.compile(r"(what else|anything else|something else|what other)(?! (could|would|might|can) (you|i|we) "
                   r"(have )?" + _CHOICE + r")|any other (problem|issue)s?")
_ALTERNATIVE = re.compile(r"(what else|anything else|what other \w+) (could|would|might|can) (you|i|we) (have )?"
                          + _CHOICE)
_SWITCH = re.compile(
    r"(what|how) about (the )?(first|second|third|last|previous|other|earlier|\d+(st|nd|rd|th)?) task|"
    r"(what|how) about task \d+|"
    r"^(and )?(the )?(first|second|third|previous|earlier) task\W*$"
)
_ORDINALS = {"first": "first", "second": "2", "third": "3", "last": "latest", "previous": "previous",
             "earlier": "previous", "other": "previous"}


# Questions about what the robot did, not about a problem: answered from the recording's content.
_WENT = re.compile(r"^(and |so |but )?why did you (go|drive|come|head|walk)( back| over)? (to|into|towards?|there)\b|"
                   r"^(and |so |but )?why did you (go|drive|come|head|walk|turn) (back|home|around)\W*$|"
                   r"^where did you (go|drive)\b|^where have you been\b|"
                   # asked of a robot on its way (a live node): the trip under way and why
                   r"^(and |so |but )?why are you (going|driving|coming|heading|walking)( back| over)? "
                   r"(to|into|towards?|there)\b|^(and |so |but )?where (are|were) you (going|heading|driving|off to)\b")
# A request to act, phrased as a question ("can you try again?"): the agent is read-only and says so.
_ACT = re.compile(r"^(and |so |ok |okay |then |now )?(please |robot |hey )?(can|could|would|will|won't|wont) you "
                  r"(please |just )?(try|retry|go|bring|fetch|get me|do it|do that|drive|move|come|start|restart|turn|"
                  r"pick|put|open|close|give|carry|deliver|make|cook|read|tell maria|recommend|suggest|choose|order)\b|"
                  r"^(and |so |ok |okay |now )?(please )?(try|do it|do that) again\b|"
                  # an order given as one, as people speak to a robot ("bring me the coffee", "go to the kitchen")
                  r"^(ok |okay |now |then |robot |hey )?(please )?(retry|go (to|back|home|and|get)|bring|fetch|"
                  r"get me|drive (to|back|home)|come (here|back|to)|start (again|over)|restart|pick (it |\w+ )?up|"
                  r"put (it|that|this|the)|open the|close the|carry|deliver)\b")
# "stop!", said to a robot: it is read-only and stops nothing, so it says what would.
_STOP = re.compile(r"^(please |robot |hey |now |ok |okay )*(stop|halt|freeze)( (it|now|moving|driving|that|there|"
                   r"right now|please|immediately))*\W*$")
_NEXT = re.compile(r"^(and |so |ok |okay )?what (are|will) you (going to |gonna )?do (next|now)\b|"
                   r"^(and |so )?what('s| is) (your |the )?next (step|move|plan)\b|"
                   r"^(and |so )?what happens (next|now)\b")
# "Will you remember this next time?": HEXAR changes nothing in how the robot acts, and says so with the fix.
_LEARN = re.compile(r"^(and |so |but |ok |okay )?(will|would|do|did|can) you (remember|learn|know better|do better|"
                    r"avoid (it|this|that))\b|^(and |so |but )?(have|did) you learn(ed|t)?\b|"
                    r"^(and |so |but |ok |okay )?(will|would|could|can|might) (it|this|that) happen again\b")
# "Are you sad?": the robot has no feelings to report; it says so with how the task ended.
_FEEL = re.compile(r"^(and |so |but |ok |okay )?(are|were) you (feeling )?(sad|happy|upset|angry|mad|frustrated|"
                   r"disappointed|embarrassed|annoyed|hurt|scared|afraid|lonely|tired|bored)\W*$|"
                   r"^(and |so )?how (do|did) you feel( about (it|this|that))?\W*$")
# "Who did you talk to?": whom the robot asked for help and what it said aloud, not a failure nobody asked about.
_TALKED = re.compile(r"^(and |so |but )?what (exactly |actually )?did you (ask|say to|tell) (her|him|them|the person|"
                     r"that person)\W*$|^(and |so |but )?what (exactly |actually )?did you ask( for)?\W*$|"
                     r"\b(who|whom) (did|have) you (talk|talked|speak|spoken|chat|chatted)( to| with)?\b|"
                     r"^(and |so |but )?did you (talk|speak) (to|with) [a-z]+\b|"
                     r"^(and |so |but )?did you (say|ask) (please|thank you|thanks|sorry|hello|hi)\b|"
                     r"^(and |so |but )?were you (polite|rude|nice)\b")
_WHERE = re.compile(r"where are you\b(?! (going|heading|driving|off to)\b)|where did you (end up|stop)\b|"
                    r"what('s| is| was) (your|the robot's|its|the robot) (position|pose|location)\W*$|"
                    r"^(and |so )?(which|what) room (are|were) you in\b|"
                    r"where('s| is) the robot\b|where did you finish\b")


# A question that names a module of the robot by what it does: of a task whose plan never ran that module, the
# answer says so ("what did you recommend?" of a coffee fetch), instead of a failure nobody asked about.
_MODULE_WORDS = {
    # "pizza" only as the one chosen ("which pizza"): "the pizza party" is a request's words, not the recommender
    "pizza_recommender": re.compile(r"\b(recommend(ed|ation)?|suggest(ed|ion)?|(which|what|that|this) pizza)\b"
                                    r"(?! (i|we|that i|that we|to|doing)\b)"),
    "ask_human_for_help": re.compile(
        r"\b(did|has|have|had) (anyone|anybody|someone|somebody|a person|people|a human) help(ed)?\b|"
        # not "who did you talk to?": the robot also talks when it only speaks a message (text_to_speech)
        r"\bask(ed)? (anyone|anybody|someone|somebody|a person|a human|people|for help)\b|"
        r"\b(who|whom) did you ask\b|"
        r"\b(get|got|getting|drive|drove|come|came|go|went) (to|up to|near|close to) (the|that) person\b|"
        # whether anyone was found: the help skill's detection, not a trip
        r"\b(was|were) (anyone|anybody|someone|somebody|people) (home|there|around)\b|"
        r"\bdid you (look for|search for|see|notice|find|detect) (me|anyone|anybody|someone|somebody|a person|"
        r"people|the person)\b|"
        r"\bwhy (didn't|did not|couldn't|could not) you (see|notice|find|detect|ask) (me|anyone|anybody|someone|"
        r"somebody|a person|the person|for help)\b|"
        # the person's distance is the help skill's measurement, not a trip of the plan
        r"\bhow (far|close|near)( away)? (was|were|is) (the|that) (person|human|people)\b"),
    # "drop off the coffee" is a delivery, which a tray robot makes without an arm; "the loop rate dropped to
    # 3.3 Hz" is a number that fell
    "manipulation": re.compile(r"\b(arm|gripper|grasp(ed|ing)?|grab(bed|bing)?|"
                               r"drop(ped|ping)?(?! (off|to|by|below|under|from|out)\b)|pick(ed|ing)? (\w+ )?up|"
                               r"plac(e|ed|ing) (it|them|that|this|the)|put (\w+ )?down)\b"),
}


# "why are scans dropped?": data a node dropped, not something the arm let fall
_DATA_DROPPED = re.compile(r"\b(scans?|messages?|msgs?|frames?|packets?|data|transforms?|tfs?|points?|clouds?|"
                           r"images?|goals?|requests?|connections?)( (are|were|is|was|being|get|got|getting))? "
                           r"dropp(ed|ing)\b|"
                           r"\bdropp(ed|ing) ([a-z0-9_]+ )?(scans?|messages?|frames?|packets?|data|transforms?)\b")


def module_asked(question: str) -> str | None:
    """The one module a question names by what it does ('manipulation' for "why did you drop it?"), else None."""
    q = normalise(question)
    named = [module for module, words in _MODULE_WORDS.items() if words.search(q)
             and not (module == "manipulation" and _DATA_DROPPED.search(q))]
    return named[0] if len(named) == 1 else None


# In this order: "stop" before a request to act, and both before the questions about what was done.
_CONTENT_KINDS = (("stop", _STOP), ("act", _ACT), ("next", _NEXT), ("learn", _LEARN), ("feel", _FEEL),
                  ("failed_at", FAILED_AT), ("goal", GOAL), ("reached", REACHED), ("at_place", AT_PLACE),
                  ("route", ROUTE), ("where", _WHERE), ("went", _WENT),
                  ("talked", _TALKED), ("person", PERSON), ("tried", TRIED), ("after", AFTER), ("tasks", TASKS),
                  ("request", REQUEST), ("doing", DOING), ("logs", LOGS), ("nodes", NODES), ("plugins", PLUGINS),
                  ("plan", PLAN), ("skills", SKILLS))


def is_order(question: str) -> bool:
    """An order to stop or to act ("stop", "bring me the coffee"), which content_kind reads as 'stop' or 'act'."""
    q = normalise(question)
    return _STOP.search(q) is not None or _ACT.search(q) is not None


def content_kind(question: str) -> str | None:
    """The kind of a question about what the robot did, its recording or where a failure lies: a moment of it
    ('at_time'), one of its nodes ('node_status'), a name of _CONTENT_KINDS, the recording's ('clock', 'recorded',
    'topic_data'), a failure's ('broken', 'fault', 'lost', 'contact',
    'blocked'), 'flag', 'limit', 'battery', 'place', a measure ('far', 'fast', 'start', 'long', 'when'), 'said', or
    'mentions' (a named thing of the stack, looked up in the log, when nothing else took it).
    Among them 'act' is a request to do something, 'stop' an order to stop, 'next' a question about what it will do;
    None for anything else."""
    from hexar.agent.moved import moved_kind
    from hexar.explainers.tts import CONTENT_QUESTION

    q = normalise(question)
    if asks_matters(q):
        return None  # "is the 'Costmap2DROS …' warning a problem?": the finding, then whether it rests on that line
    if between_asked(q) and (measure_kind(q) is None or spans_two(q)):
        return "between"  # "how long after the FATAL did spawner-4 exit?" (the task's own times are 'long', 'when')
    if ABLE.search(q):
        return "skills"  # "can you open windows at all?" asks what I can do, not for a try
    if step_asked(q):
        return "step"  # "did the place step finish cleanly?"
    # a time of day names the moment asked about (agent/window.py), a node's name the node (agent/node_status.py)
    kind = window_kind(q) or node_status_kind(q) or goal_sent_kind(q) or all_up_kind(q) or unnamed_kind(q) or \
        moved_kind(q) or \
        next((kind for kind, pattern in _CONTENT_KINDS if pattern.search(q)), None) or \
        clock_kind(q) or health_kind(q) or unseen_kind(q)
    if kind is None and flag_asked(q) is not None:
        kind = "flag"
    if kind is None and LIMIT.search(q):
        kind = "limit"
    if kind is None and BATTERY.search(q):
        kind = "battery"
    if kind is None and place_asked(q) is not None:
        kind = "place"
    if kind is None and (kind := measure_kind(q)) is None and CONTENT_QUESTION.search(q):
        kind = "said"
    if kind is None and count_asked(q):
        kind = "count"  # "how many times was a new path passed to the controller?"
    if kind is None and means_asked(q):
        kind = "means"  # "what does 'Sequences cannot be key' mean here?"
    return kind or mentions_kind(q)


# "thanks for the coffee! who put it on your tray?": a pleasantry before the question says nothing of its kind
_PLEASANTRY = re.compile(r"^(thanks|thank you|great|nice|cool|wow|ok(ay)?|hi|hello|hey|good job|well done|oh)\b"
                         r"[^.!?,]{0,60}[.!?,]+\s+(?=\S)")


def normalise(question: str) -> str:
    return _PLEASANTRY.sub("", re.sub(r"\s+", " ", question.strip().lower()))


def intent_of(question: str, has_history: bool) -> Intent:
    q = normalise(question)
    if _SWITCH.search(q):
        return "switch"
    if content_kind(q) is not None:
        return "content"
    if not has_history:
        return "new"
    if _HELPED.search(q) or _ALTERNATIVE.search(q):
        return "helped"
    if _ELSE.search(q):
        return "else"
    if _DEEPER.match(q):
        return "deeper"
    return "new"


def task_ref_of(question: str) -> str | None:
    q = normalise(question)
    m = re.search(r"(first|second|third|last|previous|other|earlier|\d+)(st|nd|rd|th)? task", q) or \
        re.search(r"task (\d+)", q)
    if not m:
        return None
    word = m.group(1)
    return word if word.isdigit() else _ORDINALS[word]
