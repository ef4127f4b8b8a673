"""Is this a question HEXAR can take? People type and speak to a robot without question marks, in statement form
("you went to the wrong place didnt you"), with "why" at the end, fillers and recogniser slips: all of that is a
question. Only what carries none is refused (empty, noise, gibberish, a greeting or a remark about nothing the
robot did), with a line saying what would work."""

from __future__ import annotations

import difflib
import re
from functools import cache

from hexar.agent.classifier import examples
from hexar.agent.errors import BadQuestionError
from hexar.agent.followups import is_order
from hexar.agent.parameters import IDENTIFIER


def _words(text: str) -> frozenset[str]:
    return frozenset(text.split())


MAX_QUESTION = 1000
"""The longest question read, in characters (CLI, chat, web, MCP and live alike): a longer one is refused
before any regular expression or model sees it, and no error message repeats more than its start."""
EXAMPLE = 'e.g. "Why didn\'t you bring me the coffee?" or "what happened"'
_WORD = re.compile(r"[a-z]+(?:'[a-z]+)?")
# Sounds and transcript markers that carry no words (whisper writes "[BLANK_AUDIO]" or "(static)" for noise).
_FILLERS = _words("um umm uh uhh uhm erm er ah ahh eh hmm hm mm mmm")
# A bracketed marker is dropped when it is all capitals or names a sound; a developer's "(9, 4)" or
# "(tolerance 0.5)" is part of the question
_MARKER = re.compile(r"\[[^\]]{0,40}\]|\([^)]{0,40}\)|<[^>]{0,40}>")
_SOUNDS = _words("music musical laughter laughs laughing laugh applause noise noises silence silent inaudible static "
                 "blank audio sound sounds cough coughs coughing sigh sighs sighing breathing breath background beep "
                 "beeps beeping clapping crosstalk unintelligible indistinct chatter buzzing humming hum wind "
                 "footsteps typing click clicks clicking unk pause foreign language speaking mumbling mumbles "
                 "whispering bell ringing phone door engine")


def _marker(m: re.Match[str]) -> str:
    inner = m.group(0)[1:-1]
    words = re.findall(r"[A-Za-z]+", inner)
    if not re.fullmatch(r"[A-Za-z_ ]*", inner):
        return m.group(0)  # digits, dots, commas: coordinates, a value, a quoted line
    if not words or inner.strip().isupper() or any(w.lower() in _SOUNDS for w in words):
        return " "
    return m.group(0)
# Typed or recognised without an apostrophe, or in chat spelling.
_SPELLING = {
    "didnt": "didn't", "dont": "don't", "doesnt": "doesn't", "cant": "can't", "couldnt": "couldn't",
    "wouldnt": "wouldn't", "shouldnt": "shouldn't", "wasnt": "wasn't", "werent": "weren't", "isnt": "isn't",
    "arent": "aren't", "havent": "haven't", "hasnt": "hasn't", "hadnt": "hadn't", "wont": "won't",
    "youre": "you're", "whats": "what's", "thats": "that's", "theres": "there's", "hows": "how's",
    "whered": "where'd", "whyd": "why'd", "im": "i'm", "ive": "i've", "u": "you", "ur": "your", "y": "why",
    "r": "are", "wat": "what", "wut": "what", "wht": "what", "wy": "why", "whyy": "why", "coz": "because",
    "cuz": "because", "pls": "please", "plz": "please",
}
_ASKING = _words("why what what's whats how how's when where where'd who whom whose which why'd whys")
_OPENERS = _words(
    "did do does was were is are can could would will should have has had didn't don't doesn't wasn't weren't "
    "isn't aren't can't couldn't wouldn't won't shouldn't haven't hasn't tell explain describe show say give list "
    "walk help talk wonder curious"
)
# A statement about what the robot did or what went wrong is a question about it ("you didnt bring it").
_ABOUT_ROBOT = _words("you your you're yourself robot tiago hexar")
_EVENTS = _words(
    "fail failed failing failure wrong stuck stopped stop late slow slowly never nothing broke broken crashed "
    "lost missed forgot gave didn't couldn't wasn't weren't won't can't problem error mistake instead "
    # a remark of surprise at what the robot did asks why it did it ("that was weird")
    "weird weirdly strange strangely odd oddly awkward awkwardly rude creepy scary funny"
)
# "i asked for coffee": reminding the robot of a request is asking why it was not done.
_REMINDERS = _words("asked wanted told said needed expected thought meant ordered requested")
# "ok so the navigation thing": naming one of the robot's modules as the topic.
_MODULES = _words("navigation navigating planner planning plan speech talking pizza recommendation recipe "
                  "localisation localization path route")
_TOPIC_MARKERS = _words("so about thing regarding re")
_TAGS = re.compile(
    r"(?:\b(?:didn't|did|don't|do|weren't|were|wasn't|was|aren't|are|isn't|is|won't|will|can't|can|couldn't|"
    r"could|haven't|have|hasn't|has) (?:you|it|they|he|she|we|i|there)|\bright|\bhuh|\beh|\bno|\bor what|\bor not|"
    r"\bwhy not|\bhow come|\bisn't it|\bwasn't it)\W*$"
)
# Nothing to explain in these on their own: greetings, thanks, acknowledgements.
_SMALL_TALK = re.compile(
    r"^(?:(?:hi|hello|hey|yo|thanks|thank|you|ok|okay|yes|yeah|yep|no|nope|sure|fine|great|good|cool|nice|bye|"
    r"goodbye|morning|evening|night|afternoon|very|much|so|a|lot|for|watching|all|right|alright|robot|tiago|"
    r"please|well|oh|wow)\b\W*)+$"
)
_COMMON = (
    "a an the i you we he she it they me my your our us him her them this that these those there here to of in on "
    "at for from with without by about into over after before again not no yes so and or but if then than too very "
    "just only also still even ever never always why what how when where who which did do does done was were is "
    "are be been being can could would will should shall may might must have has had get got go went gone come "
    "came take took make made say said tell told know think want need like see saw look find found give gave keep "
    "kept let put stop stopped start started try tried work worked happen happened wrong right long slow slowly "
    "fast quickly way thing things something anything nothing everything someone anyone nobody person people "
    "robot task room kitchen dining living bring brought fetch coffee book message maria pizza recipe help "
    "helped ask asked approach move moved moving drive driving talk talking speak speaking finish finished "
    "middle first second last other else more much many time times minute minutes second seconds fix problem "
    "that's don't didn't doesn't wasn't weren't isn't aren't can't couldn't won't wouldn't i'm you're it's "
    # beyond the example questions: how people go on about a robot's errand
    "faster slower quick quicker speed hurry late early place places spot door doors hall hallway corridor table "
    "chair sofa couch bedroom bathroom office home back forward around away toward towards close closer far "
    "farther near next front behind left turn turned turning spin spun circle circles route path way wall "
    "obstacle obstacles blocked block stuck crash crashed bump bumped hit wait waited waiting stand standing "
    "stood sit idle frozen freeze froze fail failed failing failure fails error mistake mess messed broke broken "
    "lost miss missed forgot forget gave give giving up quit sorry please hey hi hello ok okay well oh um uh "
    "actually really anyway though because since why'd what's how's where's there's won't shouldn't haven't "
    "hasn't hadn't i've you've we've they've weren't any all every each some none both one two three four five "
    "cup mug water drink tea food dinner lunch breakfast plate remote control keys phone bottle glass box list "
    "shopping agenda news weather person's man woman lady guy guys someone's human humans somebody anybody "
    "everyone everybody nobody's said saying says sentence words word voice quiet silent loud cut interrupted "
    "plan planned planning plans step steps order ordered request requested instruction instructions mean meant "
    "understand understood doing does deliver delivered delivering carry carried pick picked drop dropped "
    "recommend recommended recommendation choose chose chosen choice pick picked pizzas ingredients different "
    "same better worse best worst weird strange strangely odd oddly awkward awkwardly rude creepy scary close "
    "end ended ending reason reasons explain explanation describe show tell told answer going gonna wanna "
    "supposed able unable possible impossible instead again still yet already ago today now then while during "
    "until later soon took taking takes reach reached reaching arrive arrived arriving get getting got leave "
    "left leaving return returned returning empty handed empty-handed nothing happen happening went go goes "
    "drove drives driven walked walk walking run ran running trip errand job mission goal"
)


# A developer replaying a run asks in the words of the stack ("is use_sim_time set?", "which critic rejected it?"):
# those are questions about the robot, not words the reader does not know.
_DEVELOPER = (
    "ros nav2 moveit tf tf2 transform transforms frame frames tree node nodes topic topics parameter parameters "
    "param params yaml config configuration configured setting settings sim use clock timestamp stamp stamps "
    "tolerance tolerances threshold thresholds timeout timeouts limit limits rate rates frequency hz baud port "
    "ports device devices driver drivers serial usb firewall network dds discovery launch launched lifecycle "
    "configure activate active inactive plugin plugins controller controllers manager spawner hardware interface "
    "interfaces joint joints trajectory trajectories velocity velocities effort position command commands critic "
    "critics costmap costmaps footprint inflation radius waypoint waypoints dock docking docked undock behavior "
    "behaviour bt xml amcl odom odometry lidar scan laser imu ik kinematics solver solvers planner planners "
    "pipeline octomap collision collisions scene gripper grasp link links urdf srdf description log logs warning "
    "warnings line lines set value values loaded load running exception exceptions crash crashed died exit code "
    "simulation simulator gazebo paused pause unpause published publish publishes publishing package packages "
    "install installed permission permissions resource resources namespace namespaces initial localization "
    "localisation localize localise ekf ukf detector detectors qos durability reliability library libraries mission "
    "good bad accurate inaccurate healthy correct incorrect wifi logged sensor sensors origin bounds local global map "
    "maps out queue full"
)


@cache
def vocabulary() -> frozenset[str]:
    words = set(_COMMON.split()) | set(_DEVELOPER.split())
    for qs in examples().values():
        for q in qs:
            words.update(_WORD.findall(q.lower()))
    return frozenset(words)


@cache
def _known(word: str) -> bool:
    """In the vocabulary, or one slip away from a word of it (a typo, or a recogniser's near miss)."""
    vocab = vocabulary()
    if word in vocab or word in _SPELLING or word in _FILLERS:
        return True
    if word.endswith(("s", "ed", "ing", "ly")) and word.rstrip("s").removesuffix("ed").removesuffix("ing") in vocab:
        return True
    return len(word) >= 4 and bool(difflib.get_close_matches(word, vocab, n=1, cutoff=0.8))


def normalise(question: str) -> str:
    """Noise markers and filler sounds out, apostrophe-less contractions and chat spellings spelled out;
    everything else as asked (a well-formed question comes back unchanged)."""
    text = _MARKER.sub(_marker, question)
    text = re.sub(r"\b(would|could|should|might|must) of\b", r"\1 have", text, flags=re.I)

    def word(m: re.Match[str]) -> str:
        w = m.group(0)
        low = w.lower()
        if low in _FILLERS:
            return ""
        return _SPELLING.get(low) or _question_word(low) or w

    # a word inside an identifier (lbr_iisy11_r1300, /u2/odom) is no chat spelling: only free-standing words change
    text = re.sub(r"(?<![\w./-])[A-Za-z]+(?:'[A-Za-z]+)?(?![\w./-])", word, text)
    text = re.sub(r"\s+([,.?!])", r"\1", re.sub(r"\s+", " ", text)).strip()
    return text.lstrip(" ,.;:-")


_QUESTION_WORDS = ("where", "what", "why", "when", "which", "how")


@cache
def _question_word(word: str) -> str | None:
    """A question word typed one letter off ("wher", "whta"): the word meant. Only words the vocabulary does not
    know are corrected ("were" stays "were")."""
    if len(word) < 3 or word in vocabulary():
        return None
    for meant in _QUESTION_WORDS:
        if sorted(word) == sorted(meant):  # two letters swapped: "whta", "hwy"
            return meant
    close = difflib.get_close_matches(word, _QUESTION_WORDS, n=1, cutoff=0.85) if len(word) >= 4 else []
    return close[0] if close else None


# What to say to small talk in a conversation instead of refusing it: thanks, greetings, acknowledgements.
_THANKS = re.compile(r"\b(thanks?|thank you|thx|ty|cheers)\b")
_HELLO = re.compile(r"^(hi|hello|hey|yo|good (morning|afternoon|evening))\b")


# The end of a conversation typed or said as people end one: the chat stops on it, as on Ctrl-D.
_FAREWELL = re.compile(r"^(?:(?:ok|okay|so|well|alright|right|thanks?|thank you|that's all|that is all)\W*\s*)*"
                       r"(?:bye|bye bye|goodbye|good bye|quit|exit|see you|see ya|that's all|that is all|that's it|"
                       r"nothing else|i'm done|i am done)"
                       r"(?:\W*\s*(?:now|then|for now|robot|tiago|hexar|thanks?|thank you|bye))*\W*$")
GOODBYE = "Goodbye."


def is_farewell(text: str) -> bool:
    """Whether a turn ends the conversation ("bye", "quit", "ok that's all, thanks")."""
    return _FAREWELL.match(normalise(text).lower()) is not None


def small_talk_reply(text: str) -> str | None:
    """A reply to a turn that is only small talk ("ok thanks", "hi", "bye"), or None for anything else."""
    q = normalise(text).lower()
    if not q or not (_SMALL_TALK.match(q) or is_farewell(q)):
        return None
    if is_farewell(q):
        return GOODBYE
    if _THANKS.search(q):
        return "You're welcome. Ask me anything else about what I did."
    if _HELLO.match(q):
        return f"Hello! Ask me why I did something, {EXAMPLE}."
    return f"OK. Ask me why I did something, {EXAMPLE}."


def _asks(q: str, words: list[str]) -> bool:
    if q.endswith("?") or any(w.split("'")[0] in _ASKING for w in words) or "how come" in q:
        return True
    if words[0] in _OPENERS or (len(words) > 1 and words[0] in {"so", "and", "but", "ok", "okay", "hey", "robot",
                                                                "please", "well", "now", "then", "i"}
                                and words[1] in _OPENERS | _ASKING):
        return True
    if _TAGS.search(q) and len(words) > 2:
        return True
    if len(words) >= 3 and words[0] == "i" and words[1] in _REMINDERS:
        return True
    if any(w in _MODULES for w in words) and any(w in _TOPIC_MARKERS for w in words):
        return True
    about = any(w in _ABOUT_ROBOT for w in words) and len(words) >= 3
    return about or any(w in _EVENTS for w in words)


def bounded(question: str) -> str:
    """At most one character more than MAX_QUESTION: enough for check_question to refuse it, and nothing
    larger kept in a conversation's saved state."""
    return question[:MAX_QUESTION + 1]


def quoted(question: str, limit: int = 80) -> str:
    """The question in quotes for an error message, its start only when it is long."""
    q = question.strip()
    return repr(q) if len(q) <= limit else repr(q[:limit]) + "..."


_COPIED = re.compile(r"(?<!\w)'[^']{3,}'(?!\w)|\"[^\"]{3,}\"|“[^”]{3,}”|‘[^’]{3,}’")


def check_question(question: str) -> str:
    """The question, trimmed and normalised; raises BadQuestionError with a one-line reason otherwise."""
    if not question.strip():
        raise BadQuestionError(f"empty question: ask me why I did something, {EXAMPLE}")
    if len(question) > MAX_QUESTION:
        raise BadQuestionError(f"that question is too long: ask in at most {MAX_QUESTION} characters, {EXAMPLE}")
    q = normalise(question)
    # a log line the developer copied ("cannot access /etc/ros/humble/turtlebot4.d/*.xacro") is the log's words, not
    # the question's: it counts as one known word
    plain = _COPIED.sub(" line ", q) if _WORD.findall(_COPIED.sub(" ", q)) else q  # a quote alone: its own words
    words = _WORD.findall(plain.lower())
    # a parameter or topic by its name ("max_vel_x", "FollowPath.max_vel_x") is one word a developer knows, among
    # other words: alone, its own words must be known ("use_sim_time?", not "asdf_qwer?")
    named = _WORD.findall(IDENTIFIER.sub(" parameter ", plain.lower()))
    if len(named) > 1 and named != words:
        words = named
    if not words:
        raise BadQuestionError(f"I can't read {quoted(question)} as a question: ask me why I did something, "
                               f"{EXAMPLE}")
    known = sum(1 for w in words if _known(w))
    if known / len(words) < 0.5 or (len(words) == 1 and not _known(words[0])):
        raise BadQuestionError(f"I don't understand {quoted(question)}: ask me in words why I did something, "
                               f"{EXAMPLE}")
    if is_order(q):
        return q  # an order ("bring me the coffee", "stop"): declined as one, since the agent acts on nothing
    if _SMALL_TALK.match(q.lower()) or not _asks(q.lower(), words):
        raise BadQuestionError(f"{quoted(question)} is not a question: ask me why I did something, {EXAMPLE}")
    return q
