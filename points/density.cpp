#include "points/density.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <vector>

#include "base/error.hpp"
#include "image/image.hpp"

namespace tilekit::points {

namespace {

class Constant : public DensityFunction {
 public:
  explicit Constant(double d) : d_(d) {}
  double operator()(double, double) const override { return d_; }
  double upper_bound(double, double, double, double) const override { return d_; }
  std::string describe() const override { return fmt::format("{}", d_); }

 private:
  double d_;
};

// ---- expressions: a recursive-descent parser into a small tree --------------------------------

// Expressions are bounded before they are built: at most kMaxExpressionBytes of text and
// kMaxExpressionDepth levels of nesting (parentheses, operators, calls), so that parsing,
// evaluating and destroying the tree, all recursive, stay far inside any stack.
constexpr std::size_t kMaxExpressionBytes = 4096;
constexpr int kMaxExpressionDepth = 100;

struct Node {
  enum Kind { Num, X, Y, R, Neg, Add, Sub, Mul, Div, Pow, Call } kind = Num;
  double value = 0;
  int depth = 1;  // levels of the tree below and including this node
  std::string fn;
  std::vector<Node> args;
  double eval(double x, double y) const {
    switch (kind) {
      case Num:
        return value;
      case X:
        return x;
      case Y:
        return y;
      case R:
        return std::hypot(x, y);
      case Neg:
        return -args[0].eval(x, y);
      case Add:
        return args[0].eval(x, y) + args[1].eval(x, y);
      case Sub:
        return args[0].eval(x, y) - args[1].eval(x, y);
      case Mul:
        return args[0].eval(x, y) * args[1].eval(x, y);
      case Div:
        return args[0].eval(x, y) / args[1].eval(x, y);
      case Pow:
        return std::pow(args[0].eval(x, y), args[1].eval(x, y));
      case Call:
        return call(x, y);
    }
    return 0;
  }
  double call(double x, double y) const {
    const double a = args[0].eval(x, y);
    if (fn == "sin") return std::sin(a);
    if (fn == "cos") return std::cos(a);
    if (fn == "tan") return std::tan(a);
    if (fn == "exp") return std::exp(a);
    if (fn == "log") return std::log(a);
    if (fn == "sqrt") return std::sqrt(a);
    if (fn == "abs") return std::abs(a);
    if (fn == "floor") return std::floor(a);
    if (fn == "min") return std::min(a, args[1].eval(x, y));
    if (fn == "max") return std::max(a, args[1].eval(x, y));
    if (fn == "pow") return std::pow(a, args[1].eval(x, y));
    return std::clamp(a, args[1].eval(x, y), args[2].eval(x, y));  // clamp
  }
};

class Parser {
 public:
  explicit Parser(const std::string& s) : s_(s) {}
  Node parse() {
    if (s_.size() > kMaxExpressionBytes)
      throw InputError(fmt::format("density expression: {} bytes, more than the {} an expression may have",
                                   s_.size(), kMaxExpressionBytes));
    Node n = expr();
    skip();
    if (pos_ != s_.size()) fail("unexpected text");
    return n;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("density expression '{}': {} at position {}", s_.size() > 80 ? s_.substr(0, 77) + "..." : s_,
                                 what, pos_ + 1));
  }
  // Every node is made through here: its depth is its deepest argument's plus one, checked.
  Node node(Node::Kind k, std::vector<Node> args) {
    Node n;
    n.kind = k;
    for (const Node& a : args) n.depth = std::max(n.depth, a.depth + 1);
    if (n.depth > kMaxExpressionDepth) fail(fmt::format("nested deeper than {} levels", kMaxExpressionDepth));
    n.args = std::move(args);
    return n;
  }
  // Recursion guard of the descent itself (a long run of '(' or unary '-' before any node exists).
  struct Level {
    Parser& p;
    explicit Level(Parser& parser) : p(parser) {
      if (++p.levels_ > kMaxExpressionDepth) p.fail(fmt::format("nested deeper than {} levels", kMaxExpressionDepth));
    }
    ~Level() { --p.levels_; }
  };
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool eat(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) return ++pos_, true;
    return false;
  }
  Node bin(Node::Kind k, Node a, Node b) {
    std::vector<Node> args;
    args.push_back(std::move(a));
    args.push_back(std::move(b));
    return node(k, std::move(args));
  }
  Node expr() {
    Node n = term();
    for (;;) {
      if (eat('+'))
        n = bin(Node::Add, std::move(n), term());
      else if (eat('-'))
        n = bin(Node::Sub, std::move(n), term());
      else
        return n;
    }
  }
  Node term() {
    Node n = unary();
    for (;;) {
      if (eat('*'))
        n = bin(Node::Mul, std::move(n), unary());
      else if (eat('/'))
        n = bin(Node::Div, std::move(n), unary());
      else
        return n;
    }
  }
  Node unary() {
    const Level level(*this);
    if (eat('-')) {
      std::vector<Node> args;
      args.push_back(unary());
      return node(Node::Neg, std::move(args));
    }
    if (eat('+')) return unary();
    Node base = primary();
    if (eat('^')) return bin(Node::Pow, std::move(base), unary());
    return base;
  }
  Node primary() {
    skip();
    if (pos_ >= s_.size()) fail("expected a value");
    if (eat('(')) {
      Node n = expr();
      if (!eat(')')) fail("expected ')'");
      return n;
    }
    const char c = s_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      std::size_t used = 0;
      Node n;
      try {
        n.value = std::stod(s_.substr(pos_), &used);
      } catch (const std::exception&) {
        fail("bad number");
      }
      pos_ += used;
      return n;
    }
    if (!std::isalpha(static_cast<unsigned char>(c))) fail(fmt::format("unexpected '{}'", c));
    std::string name;
    while (pos_ < s_.size() && std::isalnum(static_cast<unsigned char>(s_[pos_]))) name += s_[pos_++];
    Node n;
    if (name == "x") return n.kind = Node::X, n;
    if (name == "y") return n.kind = Node::Y, n;
    if (name == "r") return n.kind = Node::R, n;
    if (name == "pi") return n.value = std::numbers::pi, n;
    if (name == "e") return n.value = std::numbers::e, n;
    static const std::vector<std::pair<std::string, std::size_t>> fns = {
        {"sin", 1}, {"cos", 1},   {"tan", 1}, {"exp", 1}, {"log", 1}, {"sqrt", 1},
        {"abs", 1}, {"floor", 1}, {"min", 2}, {"max", 2}, {"pow", 2}, {"clamp", 3}};
    const auto f = std::find_if(fns.begin(), fns.end(), [&](const auto& p) { return p.first == name; });
    if (f == fns.end()) fail(fmt::format("unknown name '{}'", name));
    if (!eat('(')) fail(fmt::format("expected '(' after {}", name));
    std::vector<Node> args;
    do args.push_back(expr());
    while (eat(','));
    if (!eat(')')) fail("expected ')'");
    if (args.size() != f->second) fail(fmt::format("{} takes {} argument(s)", name, f->second));
    n = node(Node::Call, std::move(args));
    n.fn = name;
    return n;
  }

  const std::string& s_;
  std::size_t pos_ = 0;
  int levels_ = 0;
};

class Expression : public DensityFunction {
 public:
  explicit Expression(std::string text) : text_(std::move(text)), root_(Parser(text_).parse()) {}
  // Every evaluation is checked: an infinite or undefined density (exp(1000), 0/0, log(-1)) is
  // bad input, never a silent 0 that would give an empty point set.
  double operator()(double x, double y) const override {
    const double v = root_.eval(x, y);
    if (!std::isfinite(v))
      throw InputError(fmt::format("density expression '{}' is {} at ({}, {}): a density must be a finite number",
                                   text_.size() > 80 ? text_.substr(0, 77) + "..." : text_,
                                   std::isnan(v) ? "undefined (NaN)" : "infinite", x, y));
    return v > 0 ? v : 0;
  }
  std::string describe() const override { return text_; }

 private:
  std::string text_;
  Node root_;
};

// ---- images ---------------------------------------------------------------------------------

class ImageDensity : public DensityFunction {
 public:
  ImageDensity(const std::string& path, const Window& where, double max_density, bool invert)
      : path_(path), w_(where), max_(max_density) {
    const Image img = read_image(path, 1);
    nx_ = img.width, ny_ = img.height;
    grey_.resize(img.pixels.size());
    for (std::size_t i = 0; i < grey_.size(); ++i)
      grey_[i] = invert ? img.pixels[i] / 255.0 : 1 - img.pixels[i] / 255.0;
    // Block maxima for upper_bound().
    bx_ = (nx_ + kBlock - 1) / kBlock, by_ = (ny_ + kBlock - 1) / kBlock;
    block_.assign(std::size_t(bx_) * std::size_t(by_), 0);
    for (int y = 0; y < ny_; ++y)
      for (int x = 0; x < nx_; ++x) {
        double& b = block_[std::size_t(y / kBlock) * std::size_t(bx_) + std::size_t(x / kBlock)];
        b = std::max(b, grey_[std::size_t(y) * std::size_t(nx_) + std::size_t(x)]);
      }
  }
  double operator()(double x, double y) const override {
    const double u = (x - w_.x0) / w_.width() * nx_ - 0.5, v = (y - w_.y0) / w_.height() * ny_ - 0.5;
    if (u < -0.5 || v < -0.5 || u > nx_ - 0.5 || v > ny_ - 0.5) return 0;
    const int i = std::clamp(int(std::floor(u)), 0, nx_ - 1), j = std::clamp(int(std::floor(v)), 0, ny_ - 1);
    const int i1 = std::min(i + 1, nx_ - 1), j1 = std::min(j + 1, ny_ - 1);
    const double fu = std::clamp(u - i, 0.0, 1.0), fv = std::clamp(v - j, 0.0, 1.0);
    const auto g = [&](int a, int b) { return grey_[std::size_t(b) * std::size_t(nx_) + std::size_t(a)]; };
    return max_ * ((g(i, j) * (1 - fu) + g(i1, j) * fu) * (1 - fv) + (g(i, j1) * (1 - fu) + g(i1, j1) * fu) * fv);
  }
  double upper_bound(double x0, double y0, double x1, double y1) const override {
    const auto px = [&](double x) { return (x - w_.x0) / w_.width() * nx_; };
    const auto py = [&](double y) { return (y - w_.y0) / w_.height() * ny_; };
    const int a0 = std::clamp(int(std::floor(px(x0))) - 1, 0, nx_ - 1) / kBlock,
              a1 = std::clamp(int(std::ceil(px(x1))) + 1, 0, nx_ - 1) / kBlock;
    const int b0 = std::clamp(int(std::floor(py(y0))) - 1, 0, ny_ - 1) / kBlock,
              b1 = std::clamp(int(std::ceil(py(y1))) + 1, 0, ny_ - 1) / kBlock;
    if (px(x1) < -1 || py(y1) < -1 || px(x0) > nx_ + 1 || py(y0) > ny_ + 1) return 0;
    double m = 0;
    for (int b = b0; b <= b1; ++b)
      for (int a = a0; a <= a1; ++a) m = std::max(m, block_[std::size_t(b) * std::size_t(bx_) + std::size_t(a)]);
    return max_ * m;
  }
  std::string describe() const override { return fmt::format("image {} ({}x{}) up to {}", path_, nx_, ny_, max_); }

 private:
  static constexpr int kBlock = 16;
  std::string path_;
  Window w_;
  double max_;
  int nx_ = 0, ny_ = 0, bx_ = 0, by_ = 0;
  std::vector<double> grey_, block_;
};

}  // namespace

std::unique_ptr<DensityFunction> constant_density(double d) {
  if (!(d > 0) || !std::isfinite(d))
    throw RequestError("density", fmt::format("`density` must be positive, got {}", d));
  return std::make_unique<Constant>(d);
}

std::unique_ptr<DensityFunction> expression_density(const std::string& text) {
  return std::make_unique<Expression>(text);
}

std::unique_ptr<DensityFunction> image_density(const std::string& path, const Window& where, double max_density,
                                               bool invert) {
  if (!(max_density > 0)) throw RequestError("density", fmt::format("`density` must be positive, got {}", max_density));
  return std::make_unique<ImageDensity>(path, where, max_density, invert);
}

}  // namespace tilekit::points
