"""Questions about what the robot did get answers from the recording, not the failure answer."""

from __future__ import annotations

from pathlib import Path

from tests.agent.helpers import converse, real_module_run


def test_why_did_you_go_and_where_are_you(suite: Path) -> None:
    went, where, said = converse(suite / "bagfile_14_1", "Why did you go to the kitchen?", "Where are you now?",
                                 "What did you say?")
    assert str(went["answer"]).startswith('I went to the kitchen because step 1 of my plan for your request "Bring '
                                          'me a coffee from the kitchen" was to go there, and I got there.')
    assert "the person did not" not in str(went["answer"])
    # after the failure the robot's recovery drove it back: the last goal of the recording
    assert str(where["answer"]).startswith("I'm in the living room")
    assert "(-1.80, 0.60)" in str(where["answer"])
    assert str(said["answer"]).startswith("I didn't say anything for your request")
    assert 'in my recovery, I said "Sorry, I could not complete the task."' in str(said["answer"])


def test_a_place_the_plan_never_went(suite: Path) -> None:
    (went,) = converse(suite / "bagfile_3_1", "Why did you go to the kitchen?")
    assert str(went["answer"]).startswith("I did not go to the kitchen for your request")
    assert "I went to the dining room and the living room" in str(went["answer"])


def test_only_a_reached_place_is_where_i_went(suite: Path) -> None:
    """bagfile_5_1 stops on the way to the kitchen: the later steps only ever waited, so no answer may say the robot
    went to the living room, and a room in no step is not answered with rooms it never reached."""
    living, dining, kitchen, anywhere = converse(suite / "bagfile_5_1", "Why did you go to the living room?",
                                                 "Why did you go to the dining room?", "Why did you go to the kitchen?",
                                                 "Where did you go?")
    assert str(living["answer"]).startswith("I did not go to the living room: step 3 of my plan")
    assert "step 1 (to go to the kitchen) failed first, so I never set off" in str(living["answer"])
    assert str(dining["answer"]).startswith("I did not go to the dining room for your request")
    assert "I tried to go to the kitchen but didn't get there, and I never set off for the living room" in \
        str(dining["answer"])
    assert str(kitchen["answer"]).startswith("I tried to go to the kitchen because step 1")
    for answer in (living, dining, kitchen, anywhere):
        assert "I went to" not in str(answer["answer"]), answer["answer"]


def test_a_recovery_trip_counts_where_the_request_never_went(suite: Path) -> None:
    """bagfile_14_1: the request never got to the living room, the recovery task drove there."""
    (went,) = converse(suite / "bagfile_14_1", "Why did you go to the living room?")
    assert str(went["answer"]).startswith("I went to the living room because step 1 of my plan for my own recovery "
                                          "task after task 1 failed (task 2)")


def test_where_when_the_robot_never_moved(suite: Path) -> None:
    (where,) = converse(suite / "bagfile_6_1", "Where are you now?")
    assert str(where["answer"]).startswith("My last goal was the kitchen, but I didn't get there")


def test_content_then_why_goes_deeper_on_it(suite: Path) -> None:
    said, why = converse(suite / "bagfile_19_2", "Did you read me the right recipe?", "why?")
    assert str(said["answer"]).startswith("No. What I said did not match your request")
    assert why["intent"] == "deeper" and "Margherita" in str(why["answer"])


def _figure(text: str, before: str) -> float:
    """The number of metres just before `before` in an answer."""
    head = text.split(before)[0].split()
    return float(head[-1])


def test_how_far_adds_up_the_legs_of_the_trip(suite: Path) -> None:
    """bagfile_10_1 fetched the coffee: each leg's figure is at least the straight line between where the leg began
    and ended, and the legs add up to the total said first."""
    from hexar.events import read_recording

    (far,) = converse(suite / "bagfile_10_1", "How far did you drive?")
    text = str(far["answer"])
    assert text.startswith('For your request "Bring me a coffee from the kitchen", I drove about ')
    kitchen, helper, back = (_figure(text, " m to go to the kitchen"), _figure(text, " m during step 2"),
                             _figure(text, " m to go to the living room"))
    total = float(text.split("I drove about ")[1].split()[0])
    assert abs(kitchen + helper + back - total) <= 0.15
    log = read_recording(suite / "bagfile_10_1")
    task = log.tasks[0]
    for run, said in ((task.skills[0], kitchen), (task.skills[2], back)):
        start = run.time_of("running")
        assert start is not None
        poses = [p for p in log.poses if start <= p.t <= run.last_change]
        straight = ((poses[-1].x - poses[0].x) ** 2 + (poses[-1].y - poses[0].y) ** 2) ** 0.5
        assert straight - 0.05 <= said <= 2 * straight


def test_how_far_on_a_trip_that_failed_or_never_moved(suite: Path) -> None:
    (failed,) = converse(suite / "bagfile_5_1", "how far did you go")
    assert ", to go to the kitchen, and I did not get there." in str(failed["answer"])
    (still,) = converse(suite / "bagfile_6_1", "How far did you travel?")  # the joystick held the base
    assert str(still["answer"]) == 'I didn\'t drive anywhere for your request "Bring me a coffee from the kitchen".'


def test_how_far_without_any_position_says_it_cannot_tell(tmp_path: Path) -> None:
    from hexar.evals.real_nav2 import corpus, write_recording

    excerpt = next(e for e in corpus() if e.outcome == "failed")
    run = write_recording(excerpt, tmp_path / "run", task=False)
    (far,) = converse(run, "How far did you drive?")
    assert "I can't tell how far I drove" in str(far["answer"])
    assert "no /amcl_pose or /odom messages" in str(far["answer"])


def test_how_long_and_when_read_the_plan_times(suite: Path) -> None:
    from hexar.events import read_recording
    from hexar.events.records import clock

    log = read_recording(suite / "bagfile_14_1")
    task, recovery = log.tasks
    took, began = converse(suite / "bagfile_14_1", "How long did it take?", "When did you start?")
    start, end = clock(task.created).split(".")[0], clock(task.last_update).split(".")[0]
    assert str(took["answer"]).startswith(f'Your request "Bring me a coffee from the kitchen" took 56 s, from {start} '
                                          f"to {end} UTC; it ended when step 2 (to ask someone for help) failed.")
    assert "Step 1 (to go to the kitchen) took 15 s; step 2 (to ask someone for help) took 41 s." in str(took["answer"])
    assert str(began["answer"]).startswith(f"I started on your request \"Bring me a coffee from the kitchen\" at "
                                           f"{start} UTC, and it ended when step 2")
    # the request never drove back; its recovery task did, and "get back" is that trip
    (back,) = converse(suite / "bagfile_14_1", "When did you get back?")
    arrived = clock(recovery.skills[0].last_change).split(".")[0]
    assert str(back["answer"]).startswith(f"In my own recovery task, I got to the living room at {arrived} UTC")
    (never,) = converse(suite / "bagfile_5_1", "When did you get back?")
    assert str(never["answer"]) == ('I never set off for the living room: that was step 3 of your request "Bring me a '
                                    'coffee from the kitchen", and step 1 (to go to the kitchen) failed first.')


def test_figures_questions_are_content_and_why_questions_are_not() -> None:
    from hexar.agent.followups import content_kind

    for question, kind in (("How far did you drive?", "far"), ("how long did it take", "long"),
                           ("How long was the trip?", "long"), ("When did you get to the kitchen?", "when"),
                           ("what time did you arrive", "when"), ("Why did it take you so long?", None),
                           ("Why did it take so long to get there?", None), ("Why didn't you get there?", None),
                           ("How long did the pick take?", "long"), ("how long did your speech take", "long"),
                           ("why did the pick take so long", None)):
        assert content_kind(question) == kind, question


def test_a_request_to_act_is_declined_not_answered_with_the_failure(suite: Path) -> None:
    """The agent is read-only: "can you try again?" gets no failure cause dressed as an answer, and no action."""
    again, bring, nxt, why = converse(suite / "bagfile_5_1", "Can you try again?", "Could you bring me the coffee?",
                                      "What are you going to do next?", "Can you tell me why you stopped?")
    for answer in (again, bring):
        text = str(answer["answer"])
        assert text.startswith("I can't do that here: here I only explain what I did"), text
        assert 'Your request "Bring me a coffee from the kitchen" failed.' in text
        assert "blocked" not in text
    assert str(nxt["answer"]).startswith("I can't tell what I will do next")
    assert "something blocked my path" in str(why["answer"])  # "can you tell me why" is a why question


def test_how_long_on_a_rejected_plan_says_it_was_rejected(suite: Path) -> None:
    """bagfile_1_1: the plan held a skill the robot lacks and was rejected; nothing was canceled."""
    (took,) = converse(suite / "bagfile_1_1", "How long did it take?")
    assert " was rejected at once, at " in str(took["answer"]), took["answer"]
    assert "before I started anything. I told you at " in str(took["answer"])
    assert "canceled" not in str(took["answer"])


def test_a_module_the_plan_never_ran_is_said_so_not_the_failure(suite: Path) -> None:
    """bagfile_5_1, a coffee fetch that failed on its first trip: a question about recommending, asking for help or
    the arm is answered with what the plan was and how far it got, not with the blocked path."""
    recommend, helped, arm, why = converse(suite / "bagfile_5_1", "What did you recommend?", "Did anyone help you?",
                                           "Why did you drop the cup?", "Why did you stop?")
    assert str(recommend["answer"]).startswith('I didn\'t recommend anything for your request "Bring me a coffee '
                                               'from the kitchen": no step of my plan was to recommend a pizza.')
    assert str(recommend["answer"]).endswith('Your request "Bring me a coffee from the kitchen" failed.')
    # the help step was planned but waited: never "I could not get help", never the blocked path as its cause
    assert str(helped["answer"]).startswith("I didn't ask anyone for help for your request")
    assert ("step 2 of my plan was to ask someone for help (\"Could you please put the coffee on my tray?\"), but I "
            "never got to it, because step 1 (to go to the kitchen) failed first.") in str(helped["answer"])
    assert str(arm["answer"]).startswith("I didn't use my arm for your request")
    for answer in (recommend, helped, arm):
        assert "blocked" not in str(answer["answer"]), answer["answer"]
    assert "something blocked my path" in str(why["answer"])


def test_after_a_step_never_reached_why_goes_on_to_the_failure_before_it(suite: Path) -> None:
    """The answer names step 1's failure as the reason: "why?" and "what would have helped?" are about it."""
    _, why, deeper, fix = converse(suite / "bagfile_5_1", "Did anyone help you?", "why?", "why?",
                                   "what would have helped?")
    assert "[controller_server] ERROR Failed to make progress" in str(why["answer"]), why["answer"]
    assert str(deeper["answer"]).startswith("I couldn't reach the kitchen because something blocked my path")
    assert fix["answer"] == "Clear the way to the kitchen and ask me again."


def test_a_module_another_task_ran_points_to_that_task(tmp_path: Path) -> None:
    """One recording, a pizza recommendation then a coffee fetch: "what did you recommend?" about the coffee says
    the pizza task did."""
    import random

    from hexar.evals.cases import scenario
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns
    from hexar.evals.scenarios.suite import EPOCH, ROOMS, Robot, normal_plan

    b = BagBuilder()
    pizza, coffee = scenario(20).variants[0], scenario(10).variants[0]
    robot = Robot(b, random.Random(3), 20, 1, sec_ns(EPOCH + 5), ROOMS[coffee.home])
    assert robot.run_task(pizza.instruction, normal_plan(pizza, 1), "")
    robot.sid = 10
    assert robot.run_task(coffee.instruction, normal_plan(coffee, 1), "")
    run = b.write(tmp_path / "two_tasks")
    recommend, helped, switched = converse(run, "What did you recommend?", "Did anyone help you?", "What about task 1?")
    text = str(recommend["answer"])
    assert text.startswith(f'I didn\'t recommend anything for your request "{coffee.instruction}"'), text
    assert text.endswith(f'In task 1, your request "{pizza.instruction}", I did: ask "what about task 1?".'), text
    # the coffee task did ask for help: that one is the ask-for-help explainer's to answer
    assert str(helped["answer"]).startswith("Asking for help went as planned"), helped["answer"]
    assert str(switched["answer"]).startswith("I recommended a "), switched["answer"]


def test_which_questions_name_a_module() -> None:
    from hexar.agent.followups import module_asked

    for question, module in (("What did you recommend?", "pizza_recommender"),
                             ("which pizza did you suggest", "pizza_recommender"),
                             ("What would you recommend I do?", None),
                             ("Did anyone help you?", "ask_human_for_help"),
                             ("who did you ask for help", "ask_human_for_help"),
                             ("who did you talk to", None),  # a message spoken is talking too
                             ("Why did you drop the cup?", "manipulation"),
                             ("Did you pick it up?", "manipulation"), ("Did you drop off the coffee?", None),
                             ("did you tell maria about the pizza party", None),
                             ("why that pizza", "pizza_recommender"), ("Why did you pick that route?", None),
                             ("Why did you go to that place?", None), ("Why did you stop?", None)):
        assert module_asked(question) == module, question


def test_an_order_without_a_question_is_declined_not_refused_or_obeyed(suite: Path) -> None:
    """"please try again", "bring me the coffee" and "stop!" are what people say to a robot: not refused as "not a
    question", not answered with the failure, and "stop" says what would stop the robot."""
    again, bring, stop, still_why = converse(suite / "bagfile_5_1", "please try again", "bring me the coffee", "Stop!",
                                             "stopped?")
    for answer in (again, bring):
        assert not answer["error"], answer
        assert str(answer["answer"]).startswith("I can't do that here: here I only explain what I did"), answer
    assert str(stop["answer"]).startswith("I can't stop from here"), stop["answer"]
    assert "press my emergency stop button" in str(stop["answer"])
    assert "blocked" not in str(stop["answer"])
    assert "something blocked my path" in str(still_why["answer"])  # "stopped?" asks why


def test_orders_and_stops_are_told_apart_from_questions() -> None:
    from hexar.agent.followups import content_kind

    for question, kind in (("stop", "stop"), ("please stop moving now", "stop"), ("go to the kitchen", "act"),
                           ("Bring me the coffee", "act"), ("try again", "act"), ("go on", None),
                           ("why did you stop", None), ("stop and tell me why", None), ("give me more details", None),
                           ("go away", None)):
        assert content_kind(question) == kind, question


def test_who_did_you_talk_to_is_whom_i_asked_and_what_i_said(suite: Path) -> None:
    """Not the failure of another step: the person the robot asked for help, then what it said aloud."""
    (declined,) = converse(suite / "bagfile_15_1", "Who did you talk to?")
    assert str(declined["answer"]).startswith('Step 2 of my plan was to ask someone for help ("Could you please '
                                              'put the coffee on my tray?"). I could not get help: the person '
                                              "declined to help."), declined["answer"]
    assert 'in my recovery, I said "Sorry, I could not complete the task."' in str(declined["answer"])
    never, why = converse(suite / "bagfile_5_1", "who did you speak with", "why?")
    assert str(never["answer"]).startswith("I didn't ask anyone for help for your request"), never["answer"]
    assert "because step 1 (to go to the kitchen) failed first. I didn't say anything either." in str(never["answer"])
    assert "[controller_server] ERROR Failed to make progress" in str(why["answer"]), why["answer"]
    (maria,) = converse(suite / "bagfile_10_3", "Did you talk to Maria?")
    assert str(maria["answer"]).startswith('Yes: I said "Maria, dinner is at eight.", which is what you asked for')
    (pizza,) = converse(suite / "bagfile_20_1", "who did you talk to")
    assert pizza["answer"] == 'I said "I recommend a Margherita."'


def test_which_questions_ask_whom_i_talked_to() -> None:
    from hexar.agent.followups import content_kind

    for question, kind in (("Who did you talk to?", "talked"), ("whom did you speak with", "talked"),
                           ("did you talk to anyone", "talked"), ("Did you speak to Maria?", "talked"),
                           ("Why did you talk to Maria?", None), ("Did anyone help you?", None),
                           ("What did you say?", "said")):
        assert content_kind(question) == kind, question


def _cut(out: Path, scenario_no: int, after_s: float) -> Path:
    """Scenario `scenario_no` recorded with rosbags and stopped `after_s` seconds after its start, as a recording
    stopped while the robot was still driving (or a live node asked then)."""
    from rosbags.rosbag2 import Writer

    from hexar.evals.cases import scenario
    from hexar.evals.scenarios.bag import TYPESTORE
    from hexar.evals.scenarios.suite import record

    messages = sorted(record(scenario(scenario_no), 1).messages, key=lambda m: m[0])
    end = messages[0][0] + int(after_s * 1e9)
    with Writer(out, version=9) as writer:
        conns: dict[tuple[str, str], object] = {}
        for t, topic, typ, m in messages:
            if t > end:
                break
            if (topic, typ) not in conns:
                conns[(topic, typ)] = writer.add_connection(topic, typ, typestore=TYPESTORE)
            writer.write(conns[(topic, typ)], t, TYPESTORE.serialize_cdr(m, typ))  # type: ignore[arg-type]
    return out


def test_where_are_you_going_is_the_trip_not_over_yet(tmp_path: Path) -> None:
    """Asked as a robot is asked on its way, in the present tense: the trip under way and the plan step behind it,
    not the robot's position; a place no step went to is still told as such."""
    run = _cut(tmp_path / "on_the_way", 5, 10.0)
    going, why, where, garage, there = converse(run, "Where are you going?", "Why are you going to the kitchen?",
                                                "Where are you?", "Why are you going to the garage?",
                                                "Why are you going there?")
    for answer in (going, why, there):
        assert str(answer["answer"]).startswith('I set off for the kitchen because step 1 of my plan for your request '
                                                '"Bring me a coffee from the kitchen" was to go there, and the '
                                                "recording ends while I was still on my way.")
    assert str(where["answer"]).startswith("My last goal was the kitchen; the recording does not show whether I got "
                                           "there.")
    assert str(garage["answer"]).startswith('I did not go to the garage for your request "Bring me a coffee from the '
                                            'kitchen": no step of my plan went there. The recording ends while I was '
                                            "still on my way to the kitchen, and I never set off for the living room.")


def test_present_tense_trips_are_went_and_where_are_you_is_where() -> None:
    from hexar.agent.followups import content_kind

    for question, kind in (("Where are you going?", "went"), ("so where are you heading", "went"),
                           ("Why are you going to the kitchen?", "went"), ("why are you driving to the door", "went"),
                           ("Where are you?", "where"), ("where are you now", "where"),
                           ("Why are you going there?", "went"), ("why did you go there", "went"),
                           ("Why are you going so slowly?", None), ("Why are you stopped?", None)):
        assert content_kind(question) == kind, question


def test_why_did_you_go_there_is_the_last_trip_not_a_place_called_there(suite: Path) -> None:
    """"There" names no place: the answer is the last trip the robot set off on and the step behind it, not "I did
    not go there"."""
    (there,) = converse(suite / "bagfile_5_1", "Why did you go there?")
    assert str(there["answer"]).startswith('I tried to go to the kitchen because step 1 of my plan for your request '
                                           '"Bring me a coffee from the kitchen" was to go there, but I didn\'t get '
                                           "there.")
    assert "did not go there" not in str(there["answer"])


def test_a_goal_read_from_nav2s_logs_is_named_as_spoken(tmp_path: Path) -> None:
    """A task derived from Nav2's logs is labelled "Navigate to an unrecorded goal (derived from Nav2)" in tables;
    an answer names it as a person would, never with that label."""
    from hexar.evals.real_nav2 import corpus, write_recording

    excerpt = next(e for e in corpus() if e.outcome == "failed")
    run = write_recording(excerpt, tmp_path / "run", task=False)
    took, after = converse(run, "How long did it take?", "What did you do after that?")
    assert str(took["answer"]).startswith("The navigation goal ")
    assert str(after["answer"]).startswith("Nothing more: the navigation goal was ")
    assert not any("derived from" in str(a["answer"]) for a in (took, after))


def test_steps_derived_from_moveit_and_ros2_control_are_said_as_steps(tmp_path: Path) -> None:
    """The steps HEXAR builds from MoveIt's, ros2_control's and Nav2's goals are said as a person says them."""
    from hexar.evals import real_nav2

    run = real_module_run("moveit2-2789-kinematics-not-passed-to-node", tmp_path / "arm")
    (doing,) = converse(run, "What were you doing when it failed?")
    assert str(doing["answer"]).startswith("When it failed at ")
    assert "I was at step 1 (to move my arm), " in str(doing["answer"])
    nav = next(e for e in real_nav2.corpus() if e.id == "nav2-3807-dwb-no-valid-trajectories")
    (took,) = converse(real_nav2.write_recording(nav, tmp_path / "nav", task=False), "How long did it take?")
    assert "it ended when step 1 (to drive to my goal) failed." in str(took["answer"])


def test_did_you_say_it_is_answered_yes_or_no_then_what(suite: Path) -> None:
    """"Did you say it out loud?" asks whether anything was said: yes (the words), no (and what the recovery said),
    or partly when the speech was cut off; whether it was what was asked stays compare()'s own yes or no."""
    (pizza,) = converse(suite / "bagfile_20_1", "did you say it out loud?")
    assert pizza["answer"] == 'Yes. I said "I recommend a Margherita."'
    (blocked,) = converse(suite / "bagfile_5_1", "Did you tell me?")
    assert blocked["answer"] == ('No. I didn\'t say anything for your request "Bring me a coffee from the kitchen". '
                                 'Afterwards, in my recovery, I said "Sorry, I could not complete the task."')
    (cut,) = converse(suite / "bagfile_19_1", "did you say anything?")
    assert str(cut["answer"]).startswith("Partly. What I said did not match your request")
    assert str(cut["answer"]).endswith("I was cut off before the end.")
    right, what = converse(suite / "bagfile_9_3", "did you say it?", "what did you say?")
    assert str(right["answer"]).startswith('Yes. I said "Maria, dinner is at eight.", which is what you asked for')
    assert str(what["answer"]).startswith('I said "Maria, dinner is at eight."')


def test_next_time_and_feelings_are_said_honestly_then_why_goes_on_to_the_failure(suite: Path) -> None:
    """HEXAR changes nothing in how the robot acts and reports no feelings: it says so, with how the task ended and,
    for "next time", what would keep the failure from happening again."""
    from hexar.agent.followups import content_kind

    assert [content_kind(q) for q in ("will you remember this next time?", "will it happen again?", "are you sad?",
                                      "how do you feel about it?", "why are you sad?")] == \
        ["learn", "learn", "feel", "feel", None]
    learn, feel, why = converse(suite / "bagfile_5_1", "will you remember this next time?", "are you sad?", "why?")
    assert learn["answer"] == ("Nothing I say here changes how I act next time: I only explain what I did, from my "
                               'recording. Your request "Bring me a coffee from the kitchen" failed. To keep it from '
                               "happening again: clear the way to the kitchen and ask me again.")
    assert str(feel["answer"]).startswith("I have no feelings to tell you about")
    assert "Failed to make progress" in str(why["answer"])  # the failure's evidence, not the task's status alone
    (fine,) = converse(suite / "bagfile_10_1", "will it happen again?")
    assert "To keep it" not in str(fine["answer"]) and str(fine["answer"]).endswith("was done.")


def test_a_specific_the_finding_leaves_out_is_answered_with_the_recorded_lines(tmp_path: Path) -> None:
    """"Which joint?": the finding names no joint, the controller's lines do; asked again, they are not retold as
    news, and "why?" then goes past them to the chain."""
    from hexar.agent.cited import asks_specific
    from hexar.evals.scenarios.arm import simulate_arm_suite

    assert [asks_specific(q) for q in ("which joint was out of tolerance?", "by how much?", "what was the tolerance?",
                                       "which room did you go to?", "which parameter should I change?")] == \
        [True, True, True, False, False]
    simulate_arm_suite(tmp_path, only=lambda s, v: v == 1 and s == "tolerance")
    joint, much, tolerance, why = converse(tmp_path / "armfile_tolerance_1", "which joint was out of tolerance?",
                                           "by how much?", "what was the tolerance?", "why?")
    assert "my arm strayed from its planned trajectory" in str(joint["answer"])
    assert 'ERROR State tolerances failed for joint 7:"' in str(joint["answer"])
    assert "Position Error: 0.199038, Position Tolerance: 0.100000" in str(joint["answer"])
    assert str(much["answer"]).startswith("I have nothing more specific on that than the lines I just quoted: at ")
    assert "strayed" not in str(much["answer"])
    assert "Position Tolerance: 0.100000" in str(tolerance["answer"])  # a follow-up, not refused as off the topic
    assert "tolerances.hpp" in str(why["answer"])  # past the quoted lines: the decisive line and its source
