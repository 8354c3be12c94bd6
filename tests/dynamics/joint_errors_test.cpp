// writeJointErrors against writeJointRows: the same counts and, row by row, the same error and
// bounds bit for bit, for every joint type, against a body and against the world, with limits
// written or not, joint friction on and off.

#include "dynamics/joint_errors.h"
#include "joint_test_util.h"

namespace af::test {
namespace {

constexpr ConstraintType kTypes[] = {ConstraintType::Fixed,  ConstraintType::BallAndSocket, ConstraintType::Universal,
                                     ConstraintType::Hinge,  ConstraintType::Slider,        ConstraintType::Spring};

void expectSameAsRows(const Joint& joint, const std::vector<RigidBody>& bodies, const JointRowSettings& settings) {
    ConstraintRows rows;
    rows.add(ConstraintRow{});  // rows already there: `first` counts them
    std::vector<RowError> errors(2);
    const JointRowRange written = writeJointRows(joint, bodies, settings, rows);
    const JointRowRange measured = writeJointErrors(joint, bodies, settings, errors);
    EXPECT_EQ(written.first, 1);
    EXPECT_EQ(measured.first, 2);
    EXPECT_EQ(measured.equalityRows, written.equalityRows);
    EXPECT_EQ(measured.limitRows, written.limitRows);
    EXPECT_EQ(measured.frictionRows, written.frictionRows);
    ASSERT_EQ(errors.size() - 2, rows.size() - 1);
    for (int r = 0; r < written.total(); ++r) {
        const ConstraintRow& row = rows[static_cast<std::size_t>(written.first + r)];
        const RowError& e = errors[static_cast<std::size_t>(measured.first + r)];
        EXPECT_EQ(e.error, row.error) << "row " << r;
        EXPECT_EQ(e.lo, row.lo) << "row " << r;
        EXPECT_EQ(e.hi, row.hi) << "row " << r;
    }
}

TEST(JointErrors, AreTheErrorsAndBoundsOfTheWrittenRows) {
    Random random(7);
    int limitRows = 0, frictionRows = 0;
    for (int trial = 0; trial < 40; ++trial)
        for (const ConstraintType type : kTypes)
            for (const int body2 : {1, kWorld}) {
                SCOPED_TRACE(std::string(toString(type)) + " trial " + std::to_string(trial));
                FigureConstraint c = randomConstraint(type, body2, random);
                c.limit = trial % 3 == 0 ? LimitType::None : type == ConstraintType::Hinge || trial % 3 == 1 ? LimitType::Cone
                                                                                                          : LimitType::Pyramid;
                c.limitAngles = {20, 30, 10};
                c.minLength = 1;
                c.maxLength = 4;
                c.friction = trial % 2;
                c.twistLimit = trial % 4 == 1 ? 15 : 0;
                auto [j, bodies] = posedJoint(c, random);
                bodies[1].position += random.vector(1);
                bodies[0].linearVelocity = random.vector(1);
                bodies[1].angularVelocity = random.vector(1);
                for (const JointRowSettings& settings : {JointRowSettings{}, allLimitRows()}) {
                    expectSameAsRows(j, bodies, settings);
                    ConstraintRows rows;
                    const JointRowRange range = writeJointRows(j, bodies, settings, rows);
                    limitRows += range.limitRows;
                    frictionRows += range.frictionRows;
                }
            }
    // The cases covered rows of every kind.
    EXPECT_GT(limitRows, 100);
    EXPECT_GT(frictionRows, 100);
}

}  // namespace
}  // namespace af::test
