"""A node's settings that ROS 2 refused as it made the node, read from the error rcl, rmw or rclpy raised (stable API).

    refused_words(text) -> tuple[str, str]

The texts are the stack catalogue's entries of these settings (explainers/stack/sources.yaml): rcl's security.c
("SECURITY ERROR: directory '%s' does not exist.", "SECURITY ERROR: unable to find a folder matching the name '%s' in
'%s'."), rcl_logging_spdlog ("Failed to create log directory '%s': %d"), the name checks of rcl and rmw ("topic name
must not contain characters other than …", raised by rclpy as "Invalid topic name: …"), and rmw_fastrtps'
"create_subscription() called for existing topic name %s with incompatible type %s", and the environment's
settings rcl and rmw refuse (a ROS_DOMAIN_ID that is not a number; security on a Fast DDS built without it). Each is
said with what the
line shows and the setting to change; what the line does not show (which file or variable gave the value) is not
claimed.
"""

from __future__ import annotations

import re

_KEYSTORE = re.compile(r"SECURITY ERROR: directory '(?P<dir>[^']*)' does not exist")
_ENCLAVE = re.compile(r"SECURITY ERROR: unable to find a folder matching the name '(?P<name>[^']*)' in "
                      r"'(?P<dir>[^']*)'")
_LOG_DIR = re.compile(r"Failed to create log directory(?: '(?P<dir>[^']*)')?")
_NAME = re.compile(r"Invalid (?P<kind>topic|node|namespace|service)(?: name)?: (?P<why>[^:]+)")
# rmw_fastrtps' topic of a service: "create_client() called for existing request topic name rq/<service>Request with
# incompatible type <pkg>::srv::dds_::<Type>_Request_" (rmw_client.cpp:169@rolling)
_SERVICE_TYPES = re.compile(r"called for existing (?:request|response) topic name r[qr](?P<service>/?[^ ]+?)"
                            r"(?:Request|Reply) with incompatible type (?P<pkg>\w+)::srv::dds_::(?P<type>\w+?)_"
                            r"(?:Request|Response)_")
# rclpy's parameter exceptions of a value the node's declaration does not take (exceptions.py@rolling)
_VALUE = re.compile(r"Invalid parameter value \((?P<value>.*?)\) for parameter\. Reason: (?P<reason>.*?)"
                    r"(?:: (?P<name>[\w.]+))?$", re.S)
_UNSET = re.compile(r"The parameter '(?P<name>[^']+)' is not initialized")
_IMMUTABLE = re.compile(r"Attempted to modify read-only parameter(?:: (?P<name>[\w.]+))?")
_TYPES = re.compile(r"called for existing topic name (?:rt)?(?P<topic>/?[^ ]+) with incompatible type "
                    r"(?P<pkg>\w+)::msg::dds_::(?P<type>\w+?)_?(?:,|$)")


def refused_words(text: str) -> tuple[str, str]:
    """(what was refused, the fix), for a person, from an error's text the stack catalogue reads as a node's settings
    that ROS 2 refused."""
    if (m := _KEYSTORE.search(text)) is not None:
        return (f"security is enabled, and the keystore it names has no such folder ({m['dir']}), so rcl could not "
                "start my node",
                "Create the keystore and this node's enclave (ros2 security create_keystore, then create_enclave) and "
                "point ROS_SECURITY_KEYSTORE at it, or turn security off for this node (ROS_SECURITY_ENABLE=false).")
    if (m := _ENCLAVE.search(text)) is not None:
        return (f"security is enabled, and the keystore ({m['dir']}) holds no enclave named {m['name']}, so rcl could "
                "not start my node",
                "Create that enclave in the keystore (ros2 security create_enclave), or give the node the enclave it "
                "has keys for (--ros-args --enclave, or ROS_SECURITY_ENCLAVE_OVERRIDE).")
    if "doesn't have the security libraries" in text:
        return ("security is enabled, but this Fast DDS was built without its security libraries, so rcl could not "
                "make my node",
                "Use a Fast DDS built with security (-DSECURITY=ON; the ROS 2 binary packages are), or turn security "
                "off for this node (ROS_SECURITY_ENABLE=false).")
    if "ROS_DOMAIN_ID is not an integral number" in text:
        return ("ROS_DOMAIN_ID is not a whole number, so rcl could not start my node",
                "Set ROS_DOMAIN_ID to a whole number from 0 to 101, the same on every computer of the robot, or "
                "unset it (domain 0).")
    if (m := _LOG_DIR.search(text)) is not None:
        where = f" ({m['dir']})" if m["dir"] else ""
        return (f"rcl could not create the folder for its log files{where}, so my node did not start",
                "Point ROS_LOG_DIR (or ROS_HOME) at a folder this user can create and write, or unset it (the "
                "default is ~/.ros/log).")
    if (m := _VALUE.search(text)) is not None:
        name = m["name"] or "a parameter"
        return (f"the value given to {name} ({m['value']}) is not one the node's declaration of it accepts "
                f"({m['reason'].strip()[:120]})",
                f"Give {name} a value the node accepts (the range or rule the reason names) where it is set: the "
                "params file, the launch file's parameters or the --ros-args overrides.")
    if (m := _UNSET.search(text)) is not None:
        return (f"the node declares the parameter {m['name']} with a type and no default value, and no value was "
                "given for it",
                f"Give {m['name']} a value where the node's parameters are set (its params file, the launch file, or "
                f"--ros-args -p {m['name']}:=...), and check that the params file names this node.")
    if (m := _IMMUTABLE.search(text)) is not None:
        name = m["name"] or "a read-only parameter"
        return (f"{name} is read-only, and a new value was given for it after the node declared it",
                "Give it its value when the node starts (params file, launch file or overrides), not later.")
    if (m := _SERVICE_TYPES.search(text)) is not None:
        service = m["service"].lstrip("/")
        return (f"two parts of one process use the service '{service}' with different service types (one of them "
                f"{m['pkg']}/srv/{m['type']}), which the middleware does not allow, so the second could not be made",
                "Use one service type per service name: give one of the two a name of its own, or make both use the "
                "same type.")
    if (m := _TYPES.search(text)) is not None:
        topic = m["topic"].lstrip("/")
        return (f"two parts of one process use the topic '{topic}' with different message types (one of them "
                f"{m['pkg']}/msg/{m['type']}), which the middleware does not allow, so the second could not be made",
                "Use one message type per topic: remap one of the two to a topic of its own, or make both use the "
                "same type.")
    if (m := _NAME.search(text)) is not None:
        return (f"a {m['kind']} name my node was given is not a valid ROS name ({m['why'].strip()})",
                f"Give a valid {m['kind']} name where it is set (a parameter, a remap or the launch file): letters, "
                "digits and underscores, with / between a topic's parts.")
    # no "refused" here: the cause vocabulary reads that word as a person who would not help (ask_human.refused)
    return (f"ROS 2 did not accept a setting of my node (“{text[:160]}”)",
            "Fix the setting the quoted error names, where the launch file, parameters or environment give it.")
