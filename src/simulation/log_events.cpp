// mlshell's -log_view events (see log_events.hpp).
#include "mlshell/log_events.hpp"

#include <map>

namespace mlshell {

PetscLogEvent log_event(const std::string& name) {
  static std::map<std::string, PetscLogEvent> events;
  static PetscClassId classid = 0;
  if (!classid) PetscClassIdRegister("mlshell", &classid);
  auto it = events.find(name);
  if (it != events.end()) return it->second;
  PetscLogEvent e;
  PetscLogEventRegister(name.c_str(), classid, &e);
  events[name] = e;
  return e;
}

}  // namespace mlshell
