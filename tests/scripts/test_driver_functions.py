"""scripts/driver_functions.py: which hardware_interface callback logs a line, read from C++ text shaped as the real
drivers are (Kinova's kortex_driver/src/hardware_interface.cpp@main: on_init checks its parameters, write() calls
sendJointCommands(), which logs "Kortex exception: " << ex.what(); prepare_command_mode_switch refuses a mix of
controllers), and the role the config gives a line by its callbacks and words."""

from __future__ import annotations

from pathlib import Path

import yaml

from tests.scripts.helpers import load_script

df = load_script("driver_functions")
CONFIG = Path(__file__).resolve().parents[2] / "scripts" / "modules_mining.yaml"

HEADER = """
namespace kortex_driver {
class KortexMultiInterfaceHardware : public hardware_interface::SystemInterface
{
public:
  CallbackReturn on_init(const hardware_interface::HardwareInfo & info) override;
  void sendJointCommands();
};
class Unrelated : public rclcpp::Node {};
}  // namespace kortex_driver
"""
SOURCE = """
namespace
{
const rclcpp::Logger LOGGER = rclcpp::get_logger("KortexMultiInterfaceHardware");
}
namespace kortex_driver
{
// don't be fooled by { braces } or "quotes { in comments
CallbackReturn KortexMultiInterfaceHardware::on_init(const hardware_interface::HardwareInfo & info)
{
  if (info_.hardware_parameters["robot_ip"].empty())
  {
    RCLCPP_ERROR(LOGGER, "Robot ip is empty!");
    return CallbackReturn::ERROR;
  }
  auto check = [&](int port) { if (port < 0) { RCLCPP_ERROR(LOGGER, "Incorrect port number!"); } };
  check(1);
  try { transport_tcp_.connect(robot_ip, 10000); }
  catch (k_api::KDetailedException & ex)
  {
    RCLCPP_ERROR_STREAM(LOGGER, "Kortex exception: " << ex.what());
  }
  return CallbackReturn::SUCCESS;
}

return_type KortexMultiInterfaceHardware::prepare_command_mode_switch(
  const std::vector<std::string> & start_interfaces, const std::vector<std::string> & stop_interfaces)
{
  RCLCPP_ERROR(LOGGER, "Can't start joint based controller while twist controller is running!");
  return return_type::ERROR;
}

return_type KortexMultiInterfaceHardware::write(const rclcpp::Time &, const rclcpp::Duration &)
{
  sendJointCommands();
  return return_type::OK;
}

void KortexMultiInterfaceHardware::sendJointCommands()
{
  char c = '{';
  try { base_cyclic_.Refresh(base_command_, 0); }
  catch (k_api::KDetailedException & ex)
  {
    RCLCPP_ERROR_STREAM(LOGGER, "Kortex exception: " << ex.what());
  }
}

void KortexMultiInterfaceHardware::neverCalled()
{
  RCLCPP_ERROR(LOGGER, "Standard exception");
}
}  // namespace kortex_driver
"""


def _callbacks(text: str, needle: str, nth: int = 0) -> tuple[str, ...]:
    table = df.callbacks_of(text, df.hardware_classes([HEADER, text]))
    at = -1
    for _ in range(nth + 1):
        at = text.index(needle, at + 1)
    return df.callbacks_at(table, at)


def test_a_class_implementing_system_interface_and_its_heirs_are_hardware_classes() -> None:
    heir = "class KortexRobotiq final : public kortex_driver::KortexMultiInterfaceHardware {};"
    assert df.hardware_classes([HEADER, heir]) == {"KortexMultiInterfaceHardware", "KortexRobotiq"}


def test_each_line_is_placed_in_the_callback_that_logs_it() -> None:
    assert _callbacks(SOURCE, "Robot ip is empty!") == ("on_init",)
    assert _callbacks(SOURCE, "Incorrect port number!") == ("on_init",)  # inside a lambda of on_init
    assert _callbacks(SOURCE, "Kortex exception") == ("on_init",)
    assert _callbacks(SOURCE, "Can't start joint based") == ("prepare_command_mode_switch",)
    # a helper only write() calls logs for write()
    assert _callbacks(SOURCE, "Kortex exception", nth=1) == ("write",)
    assert _callbacks(SOURCE, "Standard exception") == ()  # called from no callback


def test_a_line_outside_any_hardware_class_has_no_callback() -> None:
    other = "void Unrelated::read() { RCLCPP_ERROR(l, \"Unable to read from hardware...\"); }"
    assert _callbacks(other, "Unable to read") == ()


def test_blanking_keeps_offsets_and_hides_literals_and_comments() -> None:
    text = 'int a = 1\'000; // {\nauto s = "}"; /* { */ char c = \'{\';\n#define X {\n'
    code = df.blank(text)
    assert len(code) == len(text) and code.count("\n") == text.count("\n")
    assert "{" not in code and "}" not in code


def test_roles_follow_the_callbacks_and_the_lines_words() -> None:
    cfg = yaml.safe_load(CONFIG.read_text(encoding="utf-8"))["modules"]["control"]["hardware_roles"]
    assert df.role_of(["write"], "Could not send command to controller", cfg) == "exchange"
    assert df.role_of(["read"], "Unable to read from hardware...", cfg) == "exchange"
    # a command the driver cannot send is no failure to reach its device
    assert df.role_of(["write"], "Trajectory points without position information are not supported.", cfg) is None
    assert df.role_of(["on_init"], "Robot ip is empty!", cfg) == "missing"
    assert df.role_of(["on_init"], "Joint '…' has … command interfaces found. 1 expected.", cfg) == "configuration"
    assert df.role_of(["on_configure"], "Cannot connect to the Robotiq gripper", cfg) == "setup"
    assert df.role_of(["on_init"], "Could not connect to robot", cfg) == "start"
    assert df.role_of(["on_init", "write"], "Kortex exception:", cfg) == "device"
    assert df.role_of(["prepare_command_mode_switch"], "Starting … together with … is not allowed.", cfg) == "switch"
    assert df.role_of(["on_deactivate"], "Could not end FRI", cfg) is None
    assert df.role_of([], "Could not end FRI", cfg) is None


def test_foxys_configure_start_and_stop_are_callbacks_too() -> None:
    # shaped as xArm's xarm_controller/src/hardware/uf_robot_system_hardware.cpp@master (ros2_control 0.x's
    # interface): configure(info) calls the helper that reads robot_ip, read() logs a disconnected robot
    header = "class UFRobotSystemHardware : public hardware_interface::SystemInterface {};"
    text = """
namespace uf_robot_hardware
{
    void UFRobotSystemHardware::_init_ufactory_driver(void)
    {
        RCLCPP_ERROR(LOGGER, "[%s] No param named 'robot_ip'", robot_ip_.c_str());
    }
    hardware_interface::return_type UFRobotSystemHardware::configure(const hardware_interface::HardwareInfo & info)
    {
        _init_ufactory_driver();
    }
    hardware_interface::return_type UFRobotSystemHardware::read()
    {
        RCLCPP_ERROR(LOGGER, "[%s] Robot is disconnected, ros shutdown", robot_ip_.c_str());
    }
}
"""
    table = df.callbacks_of(text, df.hardware_classes([header, text]))
    assert df.callbacks_at(table, text.index("No param named")) == ("configure",)
    assert df.callbacks_at(table, text.index("Robot is disconnected")) == ("read",)
    lines = df.callbacks_by_line({"hw.hpp": header, "hw.cpp": text})["hw.cpp"]
    assert lines[text[:text.index("No param named")].count("\n") + 1] == ("configure",)
