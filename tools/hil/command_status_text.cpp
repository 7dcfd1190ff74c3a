#include "tools/hil/command_status_text.hpp"

#include "hal/axis.hpp"

namespace tnv::hil {

std::string command_status_text(fw::CommandStatus status, const fw::TickTask& task) {
  std::string text = fw::to_string(status);
  const fw::FaultRecord& fault = task.fault();
  if (status != fw::CommandStatus::faulted || !fault.active()) return text;
  text.append(" (").append(fw::to_string(fault.reason));
  if (fault.axis >= 0 && static_cast<std::size_t>(fault.axis) < hal::kAxisCount)
    text.append(", axis ").append(1, hal::axis_name(hal::axis_from_index(static_cast<std::size_t>(fault.axis))));
  text += ")";
  return text;
}

}  // namespace tnv::hil
