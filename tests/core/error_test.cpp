// The one error format: <file>:<line>: <element>: <problem> (allowed: <rule>).
#include <gtest/gtest.h>

#include "core/error.h"

namespace softsub {
namespace {

TEST(InputError, FormatsEveryPart) {
  const InputError e({"shots/goo.scene", 12, "Fluid 'honey'/Viscosity"}, "-1 is below the minimum", ">= 0");
  EXPECT_STREQ(e.what(), "shots/goo.scene:12: Fluid 'honey'/Viscosity: -1 is below the minimum (allowed: >= 0)");
  EXPECT_EQ(e.where().line, 12);
  EXPECT_EQ(e.problem(), "-1 is below the minimum");
  EXPECT_EQ(e.allowed(), ">= 0");
}

TEST(InputError, OmitsWhatIsUnknown) {
  EXPECT_STREQ(InputError({"a.sim", 0, ""}, "truncated").what(), "a.sim: truncated");
  EXPECT_STREQ(InputError({"", 3, "X"}, "bad", "good").what(), "<input>:3: X: bad (allowed: good)");
}

TEST(InputError, EscapesControlCharactersInTheFileName) {
  EXPECT_STREQ(InputError({"a\tb\n\x1b.scene", 2, "X"}, "bad").what(), "a\\tb\\n\\x1b.scene:2: X: bad");
  EXPECT_EQ(InputError({"a\tb.scene", 2, "X"}, "bad").where().file, "a\tb.scene");  // kept as it is
}

// Names and values quoted from the input (an object named "x&#10;y", a CR in a value)
// are escaped too: an error is one line, and a CR does not hide what came before it.
TEST(InputError, EscapesControlCharactersInTheElementProblemAndAllowed) {
  EXPECT_STREQ(InputError({"s.scene", 3, "Object 'x\ny'/Name"}, "'x\ny' is not a valid name", "no \r").what(),
               "s.scene:3: Object 'x\\ny'/Name: 'x\\ny' is not a valid name (allowed: no \\r)");
}

TEST(ExitCodes, AreTheDocumentedValues) {
  EXPECT_EQ(static_cast<int>(ExitCode::BadInput), 2);
  EXPECT_EQ(static_cast<int>(ExitCode::IoFailure), 3);
  EXPECT_EQ(static_cast<int>(ExitCode::BlowUp), 4);
  EXPECT_EQ(static_cast<int>(ExitCode::Interrupted), 130);
}

}  // namespace
}  // namespace softsub
