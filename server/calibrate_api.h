// Calibrate: the model fit (calibration/fit.h) behind the API, independent of the
// transport, as api.h's operations: validate, convert (calibrate.proto <->
// calibration/observations.h), one fit, convert back. The gRPC Calibrate RPC and
// `snooker calibrate` call it.
#pragma once

#include <string>
#include <vector>

#include "calibration/fit.h"
#include "calibration/observations.h"
#include "server/api.h"
#include "server/convert.h"
#include "snooker/v1/calibrate.pb.h"

namespace snooker::server {

/// The observations in library form, or the errors naming each bad observation by
/// its API path ("throw[2].cut_deg", "tracked[0].sightings[3].balls[1].id").
/// Degrees become radians here. The angles (in degrees) and the sighted positions
/// are checked here too; the other ranges by calibration::Validate (called by
/// Calibrate), whose messages Calibrate turns into the API's names.
calibration::Observations ObservationsFrom(const v1::Observations& in, std::vector<FieldError>* errors);

/// The library's observations as API messages (tracked shots' balls named "cue",
/// "ball-1", "ball-2", ...): what `snooker record` writes.
void ObservationsToProto(const calibration::Observations& in, v1::Observations* out);

/// Fits the request's groups. INVALID_ARGUMENT names the bad observation, group or
/// value, or says why the data cannot identify a group; DEADLINE_EXCEEDED when the
/// call's deadline ends the fit first; CANCELLED when the caller cancels. Never
/// changes limits.model (the start of the fit when the request gives none).
ApiStatus Calibrate(const v1::CalibrateRequest& request, v1::CalibrateResponse* response,
                    const CallLimits& limits = {});

}  // namespace snooker::server
