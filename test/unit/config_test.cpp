#include <gtest/gtest.h>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/pipeline/pipeline_config.h"

namespace tacs {
namespace {

struct InnerConfig {
  double radius = 1.0;  // [m]
  template <class V>
  void visit(V& v) {
    v("radius", radius);
  }
  void validate() const { requireConfig(radius > 0, "radius", "must be > 0"); }
};

struct OuterConfig {
  int count = 3;
  bool enabled = false;
  std::string name = "a";
  std::vector<double> values = {1.0, 2.0};
  InnerConfig inner;
  template <class V>
  void visit(V& v) {
    v("count", count);
    v("enabled", enabled);
    v("name", name);
    v("values", values);
    v("inner", inner);
  }
  void validate() const { inner.validate(); }
};

TEST(Config, MissingKeysKeepDefaults) {
  OuterConfig c;
  std::vector<std::string> unknown;
  configFromJson(parseYamlAsJson("count: 7\n", "t.yaml"), "t.yaml", &c, &unknown);
  EXPECT_EQ(c.count, 7);
  EXPECT_EQ(c.name, "a");
  EXPECT_DOUBLE_EQ(c.inner.radius, 1.0);
  EXPECT_TRUE(unknown.empty());
}

TEST(Config, ReadsEveryTypeAndNestedSections) {
  OuterConfig c;
  std::vector<std::string> unknown;
  configFromJson(parseYamlAsJson("count: 2\nenabled: true\nname: \"42\"\nvalues: [3, 4.5]\n"
                                 "inner: {radius: 2.5}\n",
                                 "t.yaml"),
                 "t.yaml", &c, &unknown);
  EXPECT_EQ(c.count, 2);
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.name, "42");  // quoted scalars stay strings
  ASSERT_EQ(c.values.size(), 2u);
  EXPECT_DOUBLE_EQ(c.values[1], 4.5);
  EXPECT_DOUBLE_EQ(c.inner.radius, 2.5);
}

TEST(Config, UnknownKeysAreReportedWithTheirPath) {
  OuterConfig c;
  std::vector<std::string> unknown;
  configFromJson(parseYamlAsJson("cuont: 2\ninner: {radus: 1}\n", "t.yaml"), "t.yaml", &c,
                 &unknown);
  ASSERT_EQ(unknown.size(), 2u);
  EXPECT_EQ(unknown[0], "inner.radus");
  EXPECT_EQ(unknown[1], "cuont");
}

std::string errorOf(const std::string& yaml) {
  OuterConfig c;
  std::vector<std::string> unknown;
  try {
    configFromJson(parseYamlAsJson(yaml, "file.yaml"), "file.yaml", &c, &unknown);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Config, WrongTypesNameFileAndKey) {
  EXPECT_EQ(errorOf("count: 2.5\n"), "file.yaml: count: expected an integer, got 2.5");
  EXPECT_EQ(errorOf("enabled: 1\n"), "file.yaml: enabled: expected true or false, got 1");
  EXPECT_EQ(errorOf("inner: {radius: abc}\n"),
            "file.yaml: inner.radius: expected a number, got \"abc\"");
  EXPECT_EQ(errorOf("values: [1, x]\n"), "file.yaml: values[1]: expected a number, got \"x\"");
  EXPECT_EQ(errorOf("inner: 3\n"), "file.yaml: inner: expected a mapping of keys");
}

TEST(Config, InvalidValuesNameTheField) {
  EXPECT_EQ(errorOf("inner: {radius: -1}\n"), "file.yaml: radius: must be > 0");
}

TEST(Config, BrokenYamlNamesFileAndLine) {
  try {
    parseYamlAsJson("a: 1\nb: [1, 2\n", "broken.yaml");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.yaml: line"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseYamlAsJson("a: 1\na: 2\n", "dup.yaml"), ConfigError);
  EXPECT_THROW(loadYamlAsJson("/nonexistent/file.yaml"), ConfigError);
}

TEST(Config, WriterRoundTripsThroughReader) {
  OuterConfig a;
  a.count = 9;
  a.inner.radius = 0.25;
  a.values = {7.0};
  OuterConfig b;
  std::vector<std::string> unknown;
  configFromJson(configToJson(a), "round-trip", &b, &unknown);
  EXPECT_EQ(b.count, 9);
  EXPECT_DOUBLE_EQ(b.inner.radius, 0.25);
  EXPECT_EQ(b.values, a.values);
  EXPECT_TRUE(unknown.empty());
}

TEST(PipelineConfig, DefaultsAreValid) { EXPECT_NO_THROW(PipelineConfig().validate()); }

TEST(PipelineConfig, FramesMustDiffer) {
  PipelineConfig c;
  c.frames.odom_frame = "map";
  EXPECT_THROW(c.validate(), ConfigError);
}

}  // namespace
}  // namespace tacs
