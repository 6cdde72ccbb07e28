#include "cli/json.h"

#include <google/protobuf/util/json_util.h>

#include <string>

namespace snooker::cli {

bool PrintJson(const google::protobuf::Message& message, const char* command, std::ostream& out,
               std::ostream& err) {
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  std::string json;
  if (!google::protobuf::util::MessageToJsonString(message, &json, options).ok()) {
    err << command << ": cannot print the result as JSON\n";
    return false;
  }
  out << json << "\n";
  return true;
}

}  // namespace snooker::cli
