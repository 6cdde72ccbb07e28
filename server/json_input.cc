#include "server/json_input.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <utility>
#include <vector>

#include "server/convert.h"
#include "snooker/v1/plan.pb.h"
#include "snooker/v1/table.pb.h"

namespace snooker::server {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::EnumDescriptor;
using google::protobuf::EnumValueDescriptor;
using google::protobuf::FieldDescriptor;

constexpr int kMaxDepth = 100;

// A string of the document: where its literal is (quotes included) and what it says.
struct StringValue {
  bool present = false;
  std::size_t begin = 0, end = 0;
  std::string text;  // decoded
};

// The document's bytes [begin, end) to be read as `with`.
struct Edit {
  std::size_t begin = 0, end = 0;
  std::string with;
};

// A BallKind or BallOn value given as a string, resolved when its object ends (a
// ball's id may follow its kind).
struct PendingEnum {
  const FieldDescriptor* field = nullptr;
  StringValue value;
};

bool TakenInAnyCase(const FieldDescriptor* field) {
  return field != nullptr && !field->is_map() &&
         (field->enum_type() == v1::BallKind_descriptor() || field->enum_type() == v1::BallOn_descriptor());
}

// "BALL_ON_" for BallOn: the prefix of an enum's value names (its name in upper snake case).
std::string ValuePrefix(const EnumDescriptor* e) {
  std::string prefix;
  for (const char c : e->name()) {
    if (std::isupper(static_cast<unsigned char>(c)) && !prefix.empty()) prefix += '_';
    prefix += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return prefix + "_";
}

void AppendUtf8(std::uint32_t cp, std::string* out) {
  if (cp < 0x80) {
    *out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    *out += static_cast<char>(0xC0 | (cp >> 6));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    *out += static_cast<char>(0xE0 | (cp >> 12));
    *out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    *out += static_cast<char>(0xF0 | (cp >> 18));
    *out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    *out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// A strict JSON reader (RFC 8259) that keeps nothing but what it is asked for: the
// first syntax error with its position and, given the message type the document
// holds, the BallKind and BallOn strings to rewrite or to report. Every loop
// consumes the text, so none runs longer than the text; nesting is bounded by
// kMaxDepth.
class Parser {
 public:
  explicit Parser(std::string_view text) : t_(text) {}

  // Reads the whole document as a `type` (null: no schema). False at the first error.
  bool Document(const Descriptor* type) {
    SkipSpace();
    if (pos_ == 0 && t_.substr(0, 3) == "\xEF\xBB\xBF") {
      return Fail("the document starts with a byte order mark: save it as UTF-8 without one");
    }
    if (pos_ >= t_.size()) return Fail("the document is empty: expected a JSON value such as {...}");
    if (!Value(nullptr, type, 0, 0, nullptr)) return false;
    SkipSpace();
    if (pos_ < t_.size()) return Fail("unexpected text after the end of the JSON document" + Found());
    return true;
  }

  const JsonSyntaxError& error() const { return error_; }
  /// Whether the document failed by nesting too deep (which no reader may take).
  bool too_deep() const { return too_deep_; }
  const std::vector<Edit>& edits() const { return edits_; }
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  // A value of `field` (null: none known); as an object, a `type` (null: none known).
  // `index`: its place in the array it is an element of. A string is kept in `string`.
  bool Value(const FieldDescriptor* field, const Descriptor* type, int depth, std::size_t index,
             StringValue* string) {
    if (pos_ >= t_.size()) return Fail("the document ends where a value was expected");
    const char c = t_[pos_];
    if ((c == '{' || c == '[') && depth >= kMaxDepth) {
      too_deep_ = true;
      return Fail("nested more than " + std::to_string(kMaxDepth) + " levels deep");
    }
    if (c == '{') return Object(type, depth + 1, index);
    if (c == '[') return Array(field, type, depth + 1);
    if (c == '"') return String(string);
    if (c == '-' || (c >= '0' && c <= '9')) return Number();
    if (c == 't') return Literal("true");
    if (c == 'f') return Literal("false");
    if (c == 'n') return Literal("null");
    return Fail("expected a value (an object, array, string, number, true, false or null)" + Found());
  }

  bool Object(const Descriptor* type, int depth, std::size_t index) {
    ++pos_;  // '{'
    SkipSpace();
    if (At('}')) return true;
    std::vector<PendingEnum> pending;
    std::optional<std::string> id;
    // The fields given so far, with the name each was given by: a field given twice
    // would lose its first value (a repeated one would join the two lists).
    std::vector<std::pair<const FieldDescriptor*, std::string>> given;
    while (pos_ < t_.size()) {
      SkipSpace();
      if (!At('"', /*consume=*/false)) {
        return Fail("expected the name of a member (a string in double quotes)" + Found());
      }
      StringValue key;
      if (!String(&key)) return false;
      SkipSpace();
      if (!At(':')) return Fail("expected ':' after the member name " + server::QuoteId(key.text) + Found());
      SkipSpace();
      const FieldDescriptor* field = FieldOf(type, key.text);
      if (field != nullptr) NoteGiven(field, key.text, &given);
      const Descriptor* member_type = field != nullptr && !field->is_map() ? field->message_type() : nullptr;
      if (field != nullptr && field->is_repeated() && !field->is_map() && pos_ < t_.size() && t_[pos_] == '{') {
        Problem(server::QuoteId(key.text) + " is an object where a list [...] is expected");
      }
      StringValue value;
      if (!Value(field, member_type, depth, 0, &value)) return false;
      if (value.present && TakenInAnyCase(field)) pending.push_back({field, value});
      if (value.present && key.text == "id") id = std::move(value.text);
      SkipSpace();
      if (pos_ >= t_.size()) break;
      if (At(',')) continue;
      if (At('}')) {
        Resolve(pending, id, index);
        return true;
      }
      return Fail("expected ',' or '}' after a member of an object" + Found());
    }
    return Fail("the document ends inside an object (no closing '}')");
  }

  // Notes `field`, given as `name`, among the object's `given` fields; a problem when
  // it was given before. The list holds at most the type's fields.
  void NoteGiven(const FieldDescriptor* field, const std::string& name,
                 std::vector<std::pair<const FieldDescriptor*, std::string>>* given) {
    const auto before = std::find_if(given->begin(), given->end(), [&](const auto& g) { return g.first == field; });
    if (before == given->end()) {
      given->emplace_back(field, name);
      return;
    }
    Problem(server::QuoteId(name) + " is given a second time in the same object" +
            (before->second == name ? std::string() : " (first as " + server::QuoteId(before->second) + ")"));
  }

  bool Array(const FieldDescriptor* field, const Descriptor* type, int depth) {
    ++pos_;  // '['
    SkipSpace();
    if (At(']')) return true;
    for (std::size_t index = 0; pos_ < t_.size(); ++index) {
      SkipSpace();
      if (type != nullptr && field != nullptr && pos_ < t_.size() && t_[pos_] != '{') {
        Problem("element " + std::to_string(index) + " (counting from 0) of " + server::QuoteId(field->json_name()) +
                " is not an object");
      }
      if (!Value(field, type, depth, index, nullptr)) return false;
      SkipSpace();
      if (pos_ >= t_.size()) break;
      if (At(',')) continue;
      if (At(']')) return true;
      return Fail("expected ',' or ']' after an element of an array" + Found());
    }
    return Fail("the document ends inside an array (no closing ']')");
  }

  bool String(StringValue* out) {
    const std::size_t begin = pos_++;  // '"'
    std::string text;
    while (pos_ < t_.size()) {
      const char c = t_[pos_];
      if (c == '"') {
        ++pos_;
        if (out != nullptr) *out = {true, begin, pos_, std::move(text)};
        return true;
      }
      if (static_cast<unsigned char>(c) < 0x20) {
        return Fail("a control character (byte " + Hex(c) +
                    ") inside a string: write it as an escape (\\n, \\t, \\u00XX)");
      }
      if (c != '\\') {
        text += c;
        ++pos_;
        continue;
      }
      if (!Escape(&text)) return false;
    }
    pos_ = begin;
    return Fail("a string that is never closed: no '\"' after it");
  }

  // One escape (at its '\'), decoded onto `text`.
  bool Escape(std::string* text) {
    static constexpr std::string_view kSimple = "\"\\/bfnrt";
    static constexpr std::string_view kMeaning = "\"\\/\b\f\n\r\t";
    if (pos_ + 1 >= t_.size()) return Fail("a string that is never closed: no '\"' after it");
    const char e = t_[pos_ + 1];
    if (const std::size_t k = kSimple.find(e); k != std::string_view::npos) {
      *text += kMeaning[k];
      pos_ += 2;
      return true;
    }
    if (e != 'u') {
      return Fail("an unknown escape '\\" + std::string(1, e) +
                  "' in a string (there are \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)");
    }
    std::uint32_t cp = 0;
    if (!Hex4(pos_ + 2, &cp)) return Fail("'\\u' must be followed by four hexadecimal digits");
    pos_ += 6;
    std::uint32_t low = 0;
    if (cp >= 0xD800 && cp <= 0xDBFF && t_.substr(pos_, 2) == "\\u" && Hex4(pos_ + 2, &low) &&
        low >= 0xDC00 && low <= 0xDFFF) {
      cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
      pos_ += 6;
    }
    // A surrogate without its pair stands for no character.
    AppendUtf8(cp >= 0xD800 && cp <= 0xDFFF ? 0xFFFD : cp, text);
    return true;
  }

  // The four hexadecimal digits at `at`, if they are.
  bool Hex4(std::size_t at, std::uint32_t* value) const {
    *value = 0;
    for (std::size_t k = at; k < at + 4; ++k) {
      const auto h = static_cast<unsigned char>(k < t_.size() ? t_[k] : '\0');
      if (!std::isxdigit(h)) return false;
      const int digit = std::isdigit(h) ? h - '0' : std::tolower(h) - 'a' + 10;
      *value = *value * 16 + static_cast<std::uint32_t>(digit);
    }
    return true;
  }

  bool Number() {
    At('-');
    if (At('0')) {
      if (pos_ < t_.size() && std::isdigit(static_cast<unsigned char>(t_[pos_]))) {
        return Fail("a number must not start with 0 followed by more digits");
      }
    } else if (!Digits()) {
      return Fail("expected a digit after '-'" + Found());
    }
    if (At('.') && !Digits()) return Fail("expected a digit after the decimal point" + Found());
    if (At('e') || At('E')) {
      if (!At('+')) At('-');
      if (!Digits()) return Fail("expected a digit in the exponent" + Found());
    }
    return true;
  }

  bool Literal(std::string_view word) {
    if (t_.substr(pos_, word.size()) != word) {
      return Fail("expected true, false or null" + Found());
    }
    pos_ += word.size();
    return true;
  }

  // The kinds and balls on of one object, now that its id (if any) is known.
  void Resolve(const std::vector<PendingEnum>& pending, const std::optional<std::string>& id,
               std::size_t index) {
    for (const PendingEnum& p : pending) {
      const EnumDescriptor* e = p.field->enum_type();
      if (const EnumValueDescriptor* v = FindInAnyCase(e, p.value.text)) {
        if (v->name() != p.value.text) {
          edits_.push_back({p.value.begin, p.value.end, "\"" + v->name() + "\""});
        }
        continue;
      }
      // `ball "red-3" has kind "purple", which` or `ballOn "purple"`.
      std::string subject = p.field->json_name() + " " + server::QuoteId(p.value.text);
      if (p.field->containing_type() == v1::Ball::descriptor()) {
        subject = (id ? "ball " + server::QuoteId(*id)
                      : "ball " + std::to_string(index) + " (counting from 0; it has no id)") +
                  " has kind " + server::QuoteId(p.value.text) + ", which";
      }
      problems_.push_back(
          LineColumnText(PositionOf(p.value.begin, subject + " is not one of " + ValueList(e) + " (in any case)")));
    }
  }

  static const FieldDescriptor* FieldOf(const Descriptor* type, const std::string& name) {
    if (type == nullptr) return nullptr;
    if (const FieldDescriptor* f = type->FindFieldByName(name)) return f;
    for (int i = 0; i < type->field_count(); ++i) {
      if (type->field(i)->json_name() == name) return type->field(i);
    }
    return nullptr;
  }

  bool Digits() {
    const std::size_t start = pos_;
    while (pos_ < t_.size() && std::isdigit(static_cast<unsigned char>(t_[pos_]))) ++pos_;
    return pos_ > start;
  }

  void SkipSpace() {
    while (pos_ < t_.size() && std::string_view(" \t\n\r").find(t_[pos_]) != std::string_view::npos) ++pos_;
  }

  // True, and past it, when the next byte is `c`.
  bool At(char c, bool consume = true) {
    if (pos_ >= t_.size() || t_[pos_] != c) return false;
    if (consume) ++pos_;
    return true;
  }

  static std::string Hex(char c) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    const auto b = static_cast<unsigned char>(c);
    return std::string("0x") + kHex[b >> 4] + kHex[b & 0xF];
  }

  // ", found 'x'" for the character `ahead` bytes on, or ", found the end of the document".
  std::string Found(std::size_t ahead = 0) const {
    const std::size_t at = pos_ + ahead;
    if (at >= t_.size()) return ", found the end of the document";
    const auto b = static_cast<unsigned char>(t_[at]);
    if (b < 0x20 || b == 0x7F) return ", found the byte " + Hex(t_[at]);
    std::size_t n = 1;  // the whole UTF-8 character
    auto continues = [&](std::size_t k) { return (static_cast<unsigned char>(t_[k]) & 0xC0) == 0x80; };
    while (b >= 0xC0 && n < 4 && at + n < t_.size() && continues(at + n)) ++n;
    return ", found '" + std::string(t_.substr(at, n)) + "'";
  }

  JsonSyntaxError PositionOf(std::size_t at, std::string what) const {
    JsonSyntaxError e{1, 1, std::move(what)};
    for (std::size_t i = 0; i < at && i < t_.size(); ++i) {
      if (t_[i] == '\n') {
        ++e.line;
        e.column = 1;
      } else if ((static_cast<unsigned char>(t_[i]) & 0xC0) != 0x80) {
        ++e.column;
      }
    }
    return e;
  }

  bool Fail(std::string what) {
    error_ = PositionOf(pos_, std::move(what));
    return false;
  }

  // Notes a problem of the document's shape at the current position.
  void Problem(std::string what) { problems_.push_back(LineColumnText(PositionOf(pos_, std::move(what)))); }

  std::string_view t_;
  std::size_t pos_ = 0;
  JsonSyntaxError error_;
  bool too_deep_ = false;
  std::vector<Edit> edits_;
  std::vector<std::string> problems_;
};

std::string Rewritten(std::string_view text, std::vector<Edit> edits) {
  // Edits are made as objects end: an object's after those of the objects inside it.
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
  std::string out;
  out.reserve(text.size());
  std::size_t from = 0;
  for (const Edit& e : edits) {
    out.append(text.substr(from, e.begin - from));
    out += e.with;
    from = e.end;
  }
  out.append(text.substr(from));
  return out;
}

}  // namespace

std::string LineColumnText(const JsonSyntaxError& e) {
  return "line " + std::to_string(e.line) + ", column " + std::to_string(e.column) + ": " + e.what;
}

std::optional<JsonSyntaxError> FindJsonSyntaxError(std::string_view text) {
  Parser parser(text);
  if (parser.Document(nullptr)) return std::nullopt;
  return parser.error();
}

bool ReadJsonMessage(std::string_view text, google::protobuf::Message* message, std::string* error) {
  Parser parser(text);
  const bool json = parser.Document(message->GetDescriptor());
  std::string rewritten;
  // A text that is not strict JSON is read as written: Protobuf's reader takes a
  // little more (single quotes, trailing commas); if it fails, the syntax error is why.
  std::string_view input = text;
  if (json) {
    const std::vector<std::string>& problems = parser.problems();
    if (!problems.empty()) {
      *error = problems.front();
      if (problems.size() > 1) *error += "; and " + std::to_string(problems.size() - 1) + " more like it";
      return false;
    }
    if (!parser.edits().empty()) {
      rewritten = Rewritten(text, parser.edits());
      input = rewritten;
    }
  }
  if (!json && parser.too_deep()) {  // Protobuf's reader would take any depth, slowly
    *error = LineColumnText(parser.error());
    return false;
  }
  const auto status = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(input.data(), input.size()), message);
  if (status.ok()) return true;
  *error = json ? std::string(status.message()) : LineColumnText(parser.error());
  return false;
}

std::string ValueList(const EnumDescriptor* e) {
  const std::string prefix = ValuePrefix(e);
  std::string list;
  for (int i = 0; i < e->value_count(); ++i) {
    if (e->value(i)->number() == 0) continue;
    std::string name = e->value(i)->name();
    if (name.compare(0, prefix.size(), prefix) == 0) name.erase(0, prefix.size());
    list += (list.empty() ? "" : ", ") + name;
  }
  return list;
}

const EnumValueDescriptor* FindInAnyCase(const EnumDescriptor* e, const std::string& text) {
  std::string upper;
  for (const char c : text) upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (const EnumValueDescriptor* v = e->FindValueByName(upper)) return v;
  return e->FindValueByName(ValuePrefix(e) + upper);
}

}  // namespace snooker::server
