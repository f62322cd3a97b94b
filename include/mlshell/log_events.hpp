// mlshell's -log_view events: one per effect ("Effect:elastic") and one per set-up phase
// ("Setup:subdivision"), all of class "mlshell", registered on first use.
#pragma once

#include <petscsys.h>

#include <string>

namespace mlshell {

/// The event called `name`, registered the first time it is asked for.
PetscLogEvent log_event(const std::string& name);

/// An event that runs for the lifetime of the object (also when an exception leaves the scope).
class LogEventScope {
 public:
  explicit LogEventScope(const std::string& name) : event_(log_event(name)) {
    PetscLogEventBegin(event_, 0, 0, 0, 0);
  }
  ~LogEventScope() { PetscLogEventEnd(event_, 0, 0, 0, 0); }
  LogEventScope(const LogEventScope&) = delete;
  LogEventScope& operator=(const LogEventScope&) = delete;

 private:
  PetscLogEvent event_;
};

/// A -log_view stage for the lifetime of the object (also when an exception leaves the scope).
class LogStageScope {
 public:
  explicit LogStageScope(PetscLogStage stage) { PetscLogStagePush(stage); }
  ~LogStageScope() { PetscLogStagePop(); }
  LogStageScope(const LogStageScope&) = delete;
  LogStageScope& operator=(const LogStageScope&) = delete;
};

}  // namespace mlshell
