#include "CameraFile.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace scenevis
{
namespace tool
{
namespace
{

std::string Number(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

/// A parsed JSON value; `offset` (into the text) places it in error messages.
struct JsonValue
{
  enum class Kind
  {
    Null,
    Boolean,
    Number,
    String,
    Array,
    Object
  };
  Kind kind = Kind::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<JsonValue> items;
  std::vector<std::pair<std::string, JsonValue>> members; ///< in file order, names unique
  std::size_t offset = 0;

  const char* KindName() const
  {
    switch (this->kind)
    {
      case Kind::Null:
        return "null";
      case Kind::Boolean:
        return "a boolean";
      case Kind::Number:
        return "a number";
      case Kind::String:
        return "a string";
      case Kind::Array:
        return "an array";
      case Kind::Object:
        return "an object";
    }
    return "a value";
  }
};

/**
 * Strict RFC 8259 JSON: what a camera file needs and nothing more lenient, so that a file that
 * other tools would read differently is refused here too. Nesting is limited (a camera file is
 * three levels deep) so that a hostile file cannot exhaust the stack.
 */
class JsonParser
{
public:
  explicit JsonParser(const std::string& text)
    : Text(text)
  {
  }

  JsonValue ParseDocument()
  {
    // A UTF-8 byte order mark is what some editors write; it is not content.
    if (this->Text.compare(0, 3, "\xEF\xBB\xBF") == 0)
      this->Pos = 3;
    this->SkipSpace();
    if (this->Pos == this->Text.size())
      this->Fail("the file is empty");
    JsonValue value = this->ParseValue(0);
    this->SkipSpace();
    if (this->Pos != this->Text.size())
      this->Fail("unexpected text after the JSON value");
    return value;
  }

  /// "line L, column C" of a text offset (1-based, columns in bytes).
  std::string Where(std::size_t offset) const
  {
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i < offset && i < this->Text.size(); ++i)
    {
      if (this->Text[i] == '\n')
      {
        ++line;
        column = 1;
      }
      else
        ++column;
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
  }

private:
  static constexpr int kMaxDepth = 32;

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw std::runtime_error(this->Where(this->Pos) + ": " + what);
  }

  void SkipSpace()
  {
    while (this->Pos < this->Text.size() &&
      (this->Text[this->Pos] == ' ' || this->Text[this->Pos] == '\t' ||
        this->Text[this->Pos] == '\n' || this->Text[this->Pos] == '\r'))
      ++this->Pos;
  }

  bool Consume(const char* literal)
  {
    const std::size_t n = std::strlen(literal);
    if (this->Text.compare(this->Pos, n, literal) != 0)
      return false;
    this->Pos += n;
    return true;
  }

  JsonValue ParseValue(int depth)
  {
    if (depth > kMaxDepth)
      this->Fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
    JsonValue value;
    value.offset = this->Pos;
    if (this->Pos >= this->Text.size())
      this->Fail("unexpected end of file");
    const char c = this->Text[this->Pos];
    if (c == '{')
      this->ParseObject(value, depth);
    else if (c == '[')
      this->ParseArray(value, depth);
    else if (c == '"')
    {
      value.kind = JsonValue::Kind::String;
      value.string = this->ParseString();
    }
    else if (c == '-' || (c >= '0' && c <= '9'))
    {
      value.kind = JsonValue::Kind::Number;
      value.number = this->ParseNumber();
    }
    else if (this->Consume("true") || this->Consume("false"))
    {
      value.kind = JsonValue::Kind::Boolean;
      value.boolean = c == 't';
    }
    else if (this->Consume("null"))
      value.kind = JsonValue::Kind::Null;
    else if (c == 'N' || c == 'n' || c == 'I' || c == 'i')
      this->Fail("NaN and Infinity are not numbers in JSON");
    else if (c > ' ' && c < 0x7F)
      this->Fail(std::string("unexpected character '") + c + "'");
    else
    {
      // Never echo a control or non-ASCII byte: the message is one printable line.
      static const char* const kHex = "0123456789abcdef";
      const auto byte = static_cast<unsigned char>(c);
      this->Fail(std::string("unexpected byte 0x") + kHex[byte >> 4] + kHex[byte & 0xF]);
    }
    return value;
  }

  void ParseObject(JsonValue& value, int depth)
  {
    value.kind = JsonValue::Kind::Object;
    ++this->Pos; // '{'
    this->SkipSpace();
    if (this->Consume("}"))
      return;
    for (;;)
    {
      this->SkipSpace();
      if (this->Pos >= this->Text.size() || this->Text[this->Pos] != '"')
        this->Fail("expected a member name in double quotes");
      const std::size_t nameAt = this->Pos;
      std::string name = this->ParseString();
      for (const auto& member : value.members)
      {
        if (member.first == name)
        {
          this->Pos = nameAt;
          this->Fail("duplicate member '" + name + "'");
        }
      }
      this->SkipSpace();
      if (!this->Consume(":"))
        this->Fail("expected ':' after member '" + name + "'");
      this->SkipSpace();
      value.members.emplace_back(std::move(name), this->ParseValue(depth + 1));
      this->SkipSpace();
      if (this->Consume("}"))
        return;
      if (!this->Consume(","))
        this->Fail(this->Pos >= this->Text.size() ? "unexpected end of file in an object"
                                                  : "expected ',' or '}' in an object");
    }
  }

  void ParseArray(JsonValue& value, int depth)
  {
    value.kind = JsonValue::Kind::Array;
    ++this->Pos; // '['
    this->SkipSpace();
    if (this->Consume("]"))
      return;
    for (;;)
    {
      this->SkipSpace();
      value.items.push_back(this->ParseValue(depth + 1));
      this->SkipSpace();
      if (this->Consume("]"))
        return;
      if (!this->Consume(","))
        this->Fail(this->Pos >= this->Text.size() ? "unexpected end of file in an array"
                                                  : "expected ',' or ']' in an array");
    }
  }

  double ParseNumber()
  {
    const std::size_t start = this->Pos;
    auto digits = [this]()
    {
      const std::size_t from = this->Pos;
      while (this->Pos < this->Text.size() && this->Text[this->Pos] >= '0' &&
        this->Text[this->Pos] <= '9')
        ++this->Pos;
      return this->Pos - from;
    };
    this->Consume("-");
    if (this->Consume("0"))
    {
      if (digits() > 0)
        this->Fail("a number must not start with 0");
    }
    else if (digits() == 0)
      this->Fail(this->Pos < this->Text.size() && (this->Text[this->Pos] == 'I')
          ? "NaN and Infinity are not numbers in JSON"
          : "expected digits in a number");
    if (this->Consume(".") && digits() == 0)
      this->Fail("expected digits after the decimal point");
    if (this->Consume("e") || this->Consume("E"))
    {
      if (!this->Consume("+"))
        this->Consume("-");
      if (digits() == 0)
        this->Fail("expected digits in the exponent");
    }
    const std::string text = this->Text.substr(start, this->Pos - start);
    errno = 0;
    const double value = std::strtod(text.c_str(), nullptr);
    if (!std::isfinite(value) || errno == ERANGE)
    {
      // Underflow to zero or a denormal is harmless; overflow to infinity is not.
      if (!std::isfinite(value) || std::abs(value) > 1.0)
      {
        this->Pos = start;
        this->Fail("number " + text + " is out of range");
      }
    }
    return value;
  }

  unsigned ParseHex4()
  {
    unsigned code = 0;
    for (int k = 0; k < 4; ++k, ++this->Pos)
    {
      const char h = this->Pos < this->Text.size() ? this->Text[this->Pos] : '\0';
      code <<= 4;
      if (h >= '0' && h <= '9')
        code |= static_cast<unsigned>(h - '0');
      else if (h >= 'a' && h <= 'f')
        code |= static_cast<unsigned>(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F')
        code |= static_cast<unsigned>(h - 'A' + 10);
      else
        this->Fail("expected 4 hexadecimal digits after \\u");
    }
    return code;
  }

  static void AppendUtf8(std::string& out, unsigned code)
  {
    if (code < 0x80)
      out += static_cast<char>(code);
    else if (code < 0x800)
    {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
    else if (code < 0x10000)
    {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
    else
    {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  std::string ParseString()
  {
    ++this->Pos; // '"'
    std::string out;
    for (;;)
    {
      if (this->Pos >= this->Text.size())
        this->Fail("unterminated string");
      const char c = this->Text[this->Pos++];
      if (c == '"')
        return out;
      if (static_cast<unsigned char>(c) < 0x20)
      {
        --this->Pos;
        this->Fail("control character in a string");
      }
      if (c != '\\')
      {
        out += c;
        continue;
      }
      const char e = this->Pos < this->Text.size() ? this->Text[this->Pos++] : '\0';
      switch (e)
      {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u':
        {
          unsigned code = this->ParseHex4();
          if (code >= 0xD800 && code <= 0xDBFF && this->Consume("\\u"))
          {
            const unsigned low = this->ParseHex4();
            if (low < 0xDC00 || low > 0xDFFF)
              this->Fail("invalid UTF-16 surrogate pair");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          else if (code >= 0xD800 && code <= 0xDFFF)
            this->Fail("lone UTF-16 surrogate");
          AppendUtf8(out, code);
          break;
        }
        default:
          --this->Pos;
          this->Fail("invalid escape in a string");
      }
    }
  }

  const std::string& Text;
  std::size_t Pos = 0;
};

/// Reads the members of one camera object into @p camera; throws with "camera N: ..." messages.
class CameraReader
{
public:
  CameraReader(const JsonValue& object, std::size_t index)
    : Object(object)
    , Prefix("camera " + std::to_string(index))
  {
  }

  CameraSpec Read(const CameraSpec& defaults) const
  {
    if (this->Object.kind != JsonValue::Kind::Object)
      this->Fail(" is " + std::string(this->Object.KindName()) +
        ", not an object {\"eye\": [x, y, z], \"focal\": [x, y, z], ...}");
    static const char* const kKnown[] = { "eye", "focal", "up", "view_angle", "parallel_scale",
      "clipping_range" };
    for (const auto& member : this->Object.members)
    {
      if (std::find_if(std::begin(kKnown), std::end(kKnown),
            [&](const char* known) { return member.first == known; }) == std::end(kKnown))
        this->Fail(": unknown member '" + member.first +
          "' (expected eye, focal, up, view_angle, parallel_scale, clipping_range)");
    }
    CameraSpec camera = defaults;
    camera.hasEye = camera.hasFocal = true;
    this->Numbers("eye", 3, camera.eye, true);
    this->Numbers("focal", 3, camera.focal, true);
    if (std::equal(camera.eye, camera.eye + 3, camera.focal))
      this->Fail(": 'eye' equals 'focal' (no view direction)");
    const bool ownUp = this->Numbers("up", 3, camera.up, false);
    camera.hasUp = camera.hasUp || ownUp;
    if (camera.hasUp)
    {
      const double d[3] = { camera.focal[0] - camera.eye[0], camera.focal[1] - camera.eye[1],
        camera.focal[2] - camera.eye[2] };
      const double* u = camera.up;
      const double cross[3] = { d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2],
        d[0] * u[1] - d[1] * u[0] };
      const double upLength = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      const double dLength = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (upLength == 0.0)
        this->Fail(": 'up' is the zero vector");
      // VTK would orthogonalise such an up vector to nothing (a NaN view).
      if (std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) <=
        1e-9 * upLength * dLength)
        this->Fail(ownUp ? ": 'up' is parallel to the view direction"
                         : ": --up is parallel to its view direction (give it an 'up')");
    }
    double angle = 0.0;
    double scale = 0.0;
    const bool hasAngle = this->Numbers("view_angle", 1, &angle, false);
    const bool hasScale = this->Numbers("parallel_scale", 1, &scale, false);
    if (hasAngle && hasScale)
      this->Fail(" has both 'view_angle' (perspective) and 'parallel_scale' (parallel)");
    if (hasAngle)
    {
      this->Check("view_angle", CheckViewAngle(angle));
      camera.viewAngle = angle;
      camera.parallel = false;
      camera.parallelScale = 0.0;
    }
    if (hasScale)
    {
      this->Check("parallel_scale", CheckParallelScale(scale));
      camera.parallelScale = scale;
      camera.parallel = true;
      camera.viewAngle = 0.0;
    }
    double range[2] = { 0.0, 0.0 };
    if (this->Numbers("clipping_range", 2, range, false))
    {
      this->Check("clipping_range", CheckClippingRange(range[0], range[1]));
      std::copy_n(range, 2, camera.clippingRange);
    }
    return camera;
  }

private:
  [[noreturn]] void Fail(const std::string& what) const
  {
    throw std::runtime_error(this->Prefix + what);
  }

  void Check(const char* name, const std::string& problem) const
  {
    if (!problem.empty())
      this->Fail(": '" + std::string(name) + "' " + problem);
  }

  /// Reads member @p name, @p count numbers (an array, or one number for count 1); false when
  /// absent and not @p required.
  bool Numbers(const char* name, std::size_t count, double* out, bool required) const
  {
    const JsonValue* value = nullptr;
    for (const auto& member : this->Object.members)
    {
      if (member.first == name)
        value = &member.second;
    }
    if (!value)
    {
      if (required)
        this->Fail(" has no '" + std::string(name) + "'");
      return false;
    }
    const std::string shape = count == 1 ? "a number"
      : count == 2                       ? "[near, far] (2 numbers)"
                                         : "[x, y, z] (3 numbers)";
    if (count == 1)
    {
      if (value->kind != JsonValue::Kind::Number)
        this->Fail(": '" + std::string(name) + "' must be " + shape + ", got " + value->KindName());
      *out = value->number;
      return true;
    }
    if (value->kind != JsonValue::Kind::Array || value->items.size() != count)
      this->Fail(": '" + std::string(name) + "' must be " + shape + ", got " +
        (value->kind == JsonValue::Kind::Array
            ? "an array of " + std::to_string(value->items.size())
            : std::string(value->KindName())));
    for (std::size_t k = 0; k < count; ++k)
    {
      if (value->items[k].kind != JsonValue::Kind::Number)
        this->Fail(": '" + std::string(name) + "' must be " + shape + ", element " +
          std::to_string(k) + " is " + value->items[k].KindName());
      out[k] = value->items[k].number;
    }
    return true;
  }

  const JsonValue& Object;
  std::string Prefix;
};
} // namespace

std::string CheckViewAngle(double degrees)
{
  if (!(degrees > 0.0 && degrees < 180.0))
    return "expects degrees in (0, 180), got " + Number(degrees);
  return std::string();
}

std::string CheckParallelScale(double scale)
{
  if (!(scale > 0.0) || !std::isfinite(scale))
    return "expects a finite scale > 0, got " + Number(scale);
  return std::string();
}

std::string CheckClippingRange(double nearDistance, double farDistance)
{
  if (!std::isfinite(nearDistance) || !std::isfinite(farDistance) || !(nearDistance > 0.0) ||
    !(nearDistance < farDistance))
    return "expects NEAR,FAR with 0 < NEAR < FAR, got " + Number(nearDistance) + "," +
      Number(farDistance);
  return std::string();
}

std::vector<CameraSpec> ReadCameraFile(const std::string& path, const CameraSpec& defaults)
{
  const std::string prefix = "--cameras '" + path + "': ";
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
    throw std::runtime_error(prefix + "cannot open (" + std::strerror(errno) + ")");
  std::string text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof(buffer), file)) > 0;)
    text.append(buffer, n);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed)
    throw std::runtime_error(prefix + "cannot read (" + std::strerror(errno) + ")");
  JsonParser parser(text);
  JsonValue document;
  try
  {
    document = parser.ParseDocument();
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(prefix + "not valid JSON: " + e.what());
  }
  if (document.kind != JsonValue::Kind::Array)
    throw std::runtime_error(
      prefix + "expects a JSON array of cameras, got " + document.KindName());
  if (document.items.empty())
    throw std::runtime_error(prefix + "has no cameras (an empty array)");
  std::vector<CameraSpec> cameras;
  try
  {
    for (std::size_t i = 0; i < document.items.size(); ++i)
      cameras.push_back(CameraReader(document.items[i], i).Read(defaults));
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(prefix + e.what());
  }
  return cameras;
}

} // namespace tool
} // namespace scenevis
