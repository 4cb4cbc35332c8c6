#include "habuffer/csg.h"

#include <algorithm>
#include <cctype>

namespace habuffer {
namespace {

// One character of the expression for a message: printable ASCII quoted, any
// other byte as \xHH (a message stays one printable line).
std::string quoted(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  const char* hex = "0123456789abcdef";
  return std::string("byte \\x") + hex[u >> 4] + hex[u & 15];
}

}  // namespace

// Recursive descent over the grammar in CsgExpression::parse's comment,
// writing postfix steps.
class CsgParser {
 public:
  CsgParser(std::string_view text, std::span<const std::string> names, CsgExpression& out)
      : text_(text), names_(names), out_(out) {}

  void run() {
    skip();
    if (at_ >= text_.size()) throw CsgError("csg expression: empty");
    out_.canonical_ = expression(0);
    skip();
    if (at_ < text_.size()) fail("unexpected " + quoted(text_[at_]));
  }

 private:
  static constexpr int kMaxDepth = 1000;

  [[noreturn]] void fail(const std::string& what) const {
    throw CsgError("csg expression, column " + std::to_string(at_ + 1) + ": " + what);
  }
  void skip() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }
  [[nodiscard]] char peek() {
    skip();
    return at_ < text_.size() ? text_[at_] : '\0';
  }

  std::string expression(int depth) {
    std::string left = term(depth);
    for (char c = peek(); c == '|' || c == '+' || c == '-'; c = peek()) {
      ++at_;
      const std::string right = term(depth);
      out_.postfix_.push_back({c == '-' ? CsgExpression::Op::Difference : CsgExpression::Op::Union, 0});
      left = "(" + left + (c == '-' ? " - " : " | ") + right + ")";
    }
    return left;
  }

  std::string term(int depth) {
    std::string left = factor(depth);
    for (char c = peek(); c == '&' || c == '*'; c = peek()) {
      ++at_;
      const std::string right = factor(depth);
      out_.postfix_.push_back({CsgExpression::Op::Intersection, 0});
      left = "(" + left + " & " + right + ")";
    }
    return left;
  }

  std::string factor(int depth) {
    if (depth > kMaxDepth) fail("nesting deeper than " + std::to_string(kMaxDepth));
    const char c = peek();
    if (c == '(') {
      ++at_;
      std::string inner = expression(depth + 1);
      if (peek() != ')') fail(at_ < text_.size() ? "expected ')' before " + quoted(text_[at_])
                                                 : "expected ')' at the end");
      ++at_;
      return inner;
    }
    if (c == '\0') fail("expected a primitive at the end");
    if (!(std::isalpha(static_cast<unsigned char>(c)) || c == '_'))
      fail("expected a primitive or '(', not " + quoted(c));
    const std::size_t start = at_;
    while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_')) ++at_;
    const std::string name(text_.substr(start, at_ - start));
    const auto found = std::find(names_.begin(), names_.end(), name);
    if (found == names_.end()) {
      at_ = start;
      fail("unknown primitive '" + name + "'");
    }
    out_.postfix_.push_back({CsgExpression::Op::Leaf, static_cast<std::uint32_t>(found - names_.begin())});
    return name;
  }

  std::string_view text_;
  std::span<const std::string> names_;
  CsgExpression& out_;
  std::size_t at_ = 0;
};

CsgExpression CsgExpression::parse(std::string_view text, std::span<const std::string> primitives) {
  if (primitives.size() > kMaxCsgPrimitives)
    throw CsgError("csg expression: " + std::to_string(primitives.size()) + " primitives, more than " +
                   std::to_string(kMaxCsgPrimitives));
  CsgExpression e;
  e.primitives_ = static_cast<std::uint32_t>(primitives.size());
  CsgParser(text, primitives, e).run();
  return e;
}

bool CsgExpression::evaluate(const CsgInside& inside) const {
  thread_local std::vector<char> stack;
  stack.clear();
  for (const Step& s : postfix_) {
    if (s.op == Op::Leaf) {
      stack.push_back(inside.test(s.leaf));
      continue;
    }
    const bool b = stack.back();
    stack.pop_back();
    const bool a = stack.back();
    stack.back() = s.op == Op::Union ? (a || b) : s.op == Op::Intersection ? (a && b) : (a && !b);
  }
  return stack.back() != 0;
}

CsgSurface csg_resolve(std::span<const ListEntry> nearest_first, const CsgExpression& expression,
                       std::uint32_t coincident) {
  CsgInside inside(expression.primitives());
  bool was = false;  // the camera is outside every primitive
  for (std::size_t i = 0; i < nearest_first.size();) {
    // Every record of this code toggled before the expression is read.
    const std::uint32_t code = nearest_first[i].code;
    std::uint32_t first = UINT32_MAX;
    bool first_exit = false;
    for (; i < nearest_first.size() && code - nearest_first[i].code <= coincident; ++i) {
      const std::uint32_t id = nearest_first[i].data >> 1;
      if (id >= expression.primitives())
        throw CsgError("csg resolve: a record names primitive " + std::to_string(id) + ", the expression has " +
                       std::to_string(expression.primitives()));
      inside.toggle(id);  // parity: a grazing pair cancels whichever facing the rasterizer gave it
      if (id < first) {
        first = id;
        first_exit = (nearest_first[i].data & 1u) != 0;
      }
    }
    const bool now = expression.evaluate(inside);
    if (now && !was) return {true, code, first, first_exit};
    was = now;
  }
  return {};
}

}  // namespace habuffer
