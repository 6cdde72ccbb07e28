// Reading JSON input (the command line's table files, shot files and requests) into
// API messages, with errors a person can act on: where a document stops being JSON
// (line and column), and which ball has a kind that does not exist. Ball kinds and
// the ball on are taken in any case ("red", "Red", "RED"). The HTTP adapter
// (connect.h) uses the syntax scanner to say where a request body stops being JSON.
#pragma once

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <optional>
#include <string>
#include <string_view>

namespace snooker::server {

/// Where a text stops being a JSON document, and why.
struct JsonSyntaxError {
  int line = 0;    ///< from 1
  int column = 0;  ///< from 1, in characters (UTF-8) of that line
  std::string what;
};

/// "line L, column C: what", as the error messages give it.
std::string LineColumnText(const JsonSyntaxError& e);

/// The first syntax error of `text` read as one JSON document (RFC 8259: an object,
/// array, string, number, true, false or null, with white space around it), or
/// nothing when it is one. Nesting deeper than 100 is an error.
std::optional<JsonSyntaxError> FindJsonSyntaxError(std::string_view text);

/// Reads the JSON document `text` (Protobuf's JSON form of `message`'s type) into
/// `message`. Before Protobuf reads it, the values of BallKind fields ("kind" of a
/// ball) and BallOn fields ("ballOn") are taken in any case: "red" and "Red" are RED,
/// and a ball on may leave out its prefix ("pink" is BALL_ON_PINK). On failure
/// returns false with a sentence in `error`:
///   "line 3, column 18: expected ',' or '}' after a member of an object, found '\"'"
///   "line 4, column 31: ball \"red-3\" has kind \"purple\", which is not one of CUE,
///    RED, YELLOW, GREEN, BROWN, BLUE, PINK, BLACK (in any case)" (a ball without an id
///   is named by its index: "ball 2 (counting from 0; it has no id)"; the first such
///   value, and how many more there are)
///   "line 1, column 52: \"balls\" is given a second time in the same object" (a
///   field given twice, by either of its names: Protobuf would keep the last value,
///   or join the lists)
/// or Protobuf's own reason for anything else (an unknown field, a string where a
/// number belongs). A text that is not strict JSON but that Protobuf's reader takes
/// anyway is read as before, without the change of case.
bool ReadJsonMessage(std::string_view text, google::protobuf::Message* message, std::string* error);

/// The value of enum `e` named `text` in any case, with or without the enum's prefix
/// ("pink", "Pink" and "BALL_ON_PINK" of BallOn), as JSON input reads it; or null.
/// The command line's flags that name a ball kind or ball on read it so too.
const google::protobuf::EnumValueDescriptor* FindInAnyCase(const google::protobuf::EnumDescriptor* e,
                                                           const std::string& text);

/// `e`'s values but the unspecified one, without their prefix: "RED, COLOUR, YELLOW, ...".
std::string ValueList(const google::protobuf::EnumDescriptor* e);

}  // namespace snooker::server
