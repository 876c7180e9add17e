// rig::Table in Bullet: a multibody (carriage, yoke, plate) in reduced coordinates, driven by
// servos at the physics rate.
#include "casmap/rig/table.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <LinearMath/btAlignedObjectArray.h>

#include <cmath>
#include <initializer_list>
#include <memory>
#include <numbers>

namespace casmap::rig {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kGravity = 9.81;
// Masses (kg): carriage, pitch yoke, roll plate carrying the LMS 200 (4.5 kg, manual).
constexpr double kCarriageKg = 10.0;
constexpr double kYokeKg = 3.0;
constexpr double kPlateKg = 6.0;

btVector3 ToBt(const Eigen::Vector3d& v) {
    return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
            static_cast<btScalar>(v.z())};
}

Eigen::Vector3d FromBt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

core::Pose FromBt(const btTransform& t) {
    const btQuaternion q = t.getRotation();
    return core::Pose{FromBt(t.getOrigin()),
                      Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized()};
}

// Half extents (m) of the parts' boxes, for their inertias.
const btVector3 kCarriageHalf(0.20F, 0.15F, 0.05F);
const btVector3 kYokeHalf(0.10F, 0.10F, 0.10F);
const btVector3 kPlateHalf(0.08F, 0.08F, 0.09F);

// Link indices of the multibody (the base is fixed at the pitch-axis origin).
constexpr int kCarriage = 0;
constexpr int kYoke = 1;
constexpr int kPlate = 2;

btVector3 BoxInertia(double mass_kg, const btVector3& half) {
    const auto m = static_cast<btScalar>(mass_kg / 3.0);
    return {m * (half.y() * half.y() + half.z() * half.z()),
            m * (half.x() * half.x() + half.z() * half.z()),
            m * (half.x() * half.x() + half.y() * half.y())};
}

/// The table as one Bullet multibody in reduced coordinates (Featherstone): a prismatic
/// carriage along world x, the yoke on a revolute joint about the carriage's y (pitch), the
/// plate on a revolute joint about the yoke's x (roll). Joint coordinates are casmap's joint
/// values (Bullet turns a link by +q about its axis), so the joints cannot drift apart and no
/// collision detection or iterative joint solver runs. Nothing is allocated per step.
class TableBody {
public:
    TableBody(const TableGeometry& geometry, const TableJoints& start, const TableJoints& rate)
        : body_(3, 1.0F, btVector3(1, 1, 1), /*fixedBase=*/true, /*canSleep=*/false) {
        const btQuaternion none = btQuaternion::getIdentity();
        const btVector3 zero(0, 0, 0);
        body_.setBaseWorldTransform(btTransform(none, ToBt(geometry.pitch_axis_origin_m)));
        body_.setupPrismatic(kCarriage, static_cast<btScalar>(kCarriageKg),
                             BoxInertia(kCarriageKg, kCarriageHalf), -1, none, btVector3(1, 0, 0),
                             zero, zero, true);
        body_.setupRevolute(kYoke, static_cast<btScalar>(kYokeKg), BoxInertia(kYokeKg, kYokeHalf),
                            kCarriage, none, btVector3(0, 1, 0), zero, zero, true);
        // The plate's centre of mass is the scanner origin: its frame is the sensor frame.
        body_.setupRevolute(
            kPlate, static_cast<btScalar>(kPlateKg), BoxInertia(kPlateKg, kPlateHalf), kYoke, none,
            btVector3(1, 0, 0), ToBt(geometry.pitch_to_roll_m),
            btVector3(0, 0, static_cast<btScalar>(geometry.roll_to_sensor_m)), true);
        body_.finalizeMultiDof();
        body_.setLinearDamping(0);
        body_.setAngularDamping(0);
        body_.setHasSelfCollision(false);
        const double q[3] = {start.linear_m, start.pitch_rad, start.roll_rad};
        const double v[3] = {rate.linear_m, rate.pitch_rad, rate.roll_rad};
        for (int i = 0; i < 3; ++i) {
            body_.setJointPos(i, static_cast<btScalar>(q[i]));
            body_.setJointVel(i, static_cast<btScalar>(v[i]));
        }
        world_to_local_.resize(4);
        local_origin_.resize(4);
        UpdateTransforms();
    }

    btMultiBody& body() { return body_; }
    [[nodiscard]] const btTransform& LinkTransform(int link) const {
        return body_.getLink(link).m_cachedWorldTransform;
    }
    void UpdateTransforms() { body_.forwardKinematics(world_to_local_, local_origin_); }

    /// Bullet's articulated-body step of the velocities under gravity and the joint torques
    /// added since the last clearForcesAndTorques().
    void IntegrateForces(double dt) {
        for (int i = 0; i < 3; ++i) {
            body_.addLinkForce(
                i, btVector3(0, 0, static_cast<btScalar>(-kGravity) * body_.getLinkMass(i)));
        }
        body_.computeAccelerationsArticulatedBodyAlgorithmMultiDof(
            static_cast<btScalar>(dt), scratch_r_, scratch_v_, scratch_m_, false, false, false);
        body_.clearForcesAndTorques();
    }

    /// The impulse along joint `link` alone that sets its rate to `target` (a stiff servo on
    /// one joint; it moves the others through the coupling): one exact constraint row.
    void ServoImpulse(int link, double target) {
        btScalar unit[9] = {};
        unit[6 + link] = 1;
        btScalar response[9] = {};
        body_.calcAccelerationDeltasMultiDof(unit, response, scratch_r_, scratch_v_);
        const btScalar lambda =
            (static_cast<btScalar>(target) - body_.getJointVel(link)) / response[6 + link];
        body_.applyDeltaVeeMultiDof(response, lambda);
    }

private:
    btMultiBody body_;
    btAlignedObjectArray<btQuaternion> world_to_local_;
    btAlignedObjectArray<btVector3> local_origin_;
    btAlignedObjectArray<btScalar> scratch_r_;
    btAlignedObjectArray<btVector3> scratch_v_;
    btAlignedObjectArray<btMatrix3x3> scratch_m_;
};

/// Joint values and rates: Bullet's joint coordinates.
void MeasureJoints(const btMultiBody& body, TableJoints& value, TableJoints& rate) {
    value.linear_m = body.getJointPos(kCarriage);
    value.pitch_rad = body.getJointPos(kYoke);
    value.roll_rad = body.getJointPos(kPlate);
    rate.linear_m = body.getJointVel(kCarriage);
    rate.pitch_rad = body.getJointVel(kYoke);
    rate.roll_rad = body.getJointVel(kPlate);
}

/// Moment of inertia (kg m^2) of link `i` about the axis through `pivot` along unit `axis`.
double InertiaAbout(const TableBody& table,
                    const btMultiBody& body,
                    int i,
                    const btVector3& pivot,
                    const btVector3& axis) {
    const btTransform& t = table.LinkTransform(i);
    const btVector3 local_axis = t.getBasis().transpose() * axis;
    const btVector3& inertia = body.getLinkInertia(i);
    double i_axis = 0.0;
    for (int k = 0; k < 3; ++k) {
        i_axis += local_axis[k] * local_axis[k] * inertia[k];
    }
    const double lever = (t.getOrigin() - pivot).cross(axis).length();
    return i_axis + lever * lever * body.getLinkMass(i);
}

/// Gravity torque (N m) about the axis through `pivot` of the links in `distal`.
double GravityTorque(const TableBody& table,
                     const btMultiBody& body,
                     std::initializer_list<int> distal,
                     const btVector3& pivot,
                     const btVector3& axis) {
    double torque = 0.0;
    for (const int i : distal) {
        const btVector3 weight(0, 0, static_cast<btScalar>(-kGravity) * body.getLinkMass(i));
        torque += (table.LinkTransform(i).getOrigin() - pivot).cross(weight).dot(axis);
    }
    return torque;
}

struct Commands {
    TableJoints value;
    TableJoints rate;
};

Commands CommandAt(const SpeedSchedule& schedule,
                   const AngleProfile& roll,
                   const AngleProfile& pitch,
                   double t_s) {
    const ProfileSample x = schedule.Evaluate(t_s);
    const ProfileSample r = EvaluateProfile(roll, t_s);
    const ProfileSample p = EvaluateProfile(pitch, t_s);
    return {TableJoints{x.value_rad, r.value_rad, p.value_rad},
            TableJoints{x.rate_rad_s, r.rate_rad_s, p.rate_rad_s}};
}

/// The joints' drives at the physics rate: the carriage is always a dead-beat velocity servo
/// (the rate that lands on the command next step); the rotary joints are the same rigid
/// servos, or the compliant spring-damper servo with gravity feed-forward.
class Drive {
public:
    Drive(TableBody& table, const TableConfig& config, const TableGeometry& geometry)
        : pitch_to_roll_(ToBt(geometry.pitch_to_roll_m)),
          dt_(1.0 / config.physics_rate_hz),
          compliant_(config.compliance.enabled),
          wn_(2.0 * std::numbers::pi * config.compliance.natural_frequency_hz),
          zeta_(config.compliance.damping_ratio) {
        // Inertias of the distal links about each axis, taken at the start pose.
        const btMultiBody& body = table.body();
        const btTransform& yoke = table.LinkTransform(kYoke);
        const btVector3 pitch_axis(0, 1, 0);
        pitch_inertia_ = InertiaAbout(table, body, kYoke, yoke.getOrigin(), pitch_axis) +
                         InertiaAbout(table, body, kPlate, yoke.getOrigin(), pitch_axis);
        roll_inertia_ =
            InertiaAbout(table, body, kPlate, RollPivot(table), yoke.getBasis().getColumn(0));
    }

    /// Sets the joint rates for the step to the next command.
    void Step(TableBody& table, const Commands& cmd, const TableJoints& q, const TableJoints& qd) {
        btMultiBody& body = table.body();
        const double linear_rate = (cmd.value.linear_m - q.linear_m) / dt_;
        if (!compliant_) {
            // Stiff servos on every joint: the rates are the dead-beat commands whatever the
            // loads, so the rigid table follows the command exactly at each step.
            body.setJointVel(kCarriage, static_cast<btScalar>(linear_rate));
            body.setJointVel(kYoke,
                             static_cast<btScalar>((cmd.value.pitch_rad - q.pitch_rad) / dt_));
            body.setJointVel(kPlate,
                             static_cast<btScalar>((cmd.value.roll_rad - q.roll_rad) / dt_));
            return;
        }
        // Spring-damper servo with gravity feed-forward (a real drive's integral action), so
        // the table rings about its command instead of sagging.
        const btTransform& yoke = table.LinkTransform(kYoke);
        const double pitch_torque =
            Spring(pitch_inertia_, cmd.value.pitch_rad - q.pitch_rad,
                   cmd.rate.pitch_rad - qd.pitch_rad) -
            GravityTorque(table, body, {kYoke, kPlate}, yoke.getOrigin(), btVector3(0, 1, 0));
        const double roll_torque =
            Spring(roll_inertia_, cmd.value.roll_rad - q.roll_rad,
                   cmd.rate.roll_rad - qd.roll_rad) -
            GravityTorque(table, body, {kPlate}, RollPivot(table), yoke.getBasis().getColumn(0));
        body.addJointTorque(kYoke, static_cast<btScalar>(pitch_torque));
        body.addJointTorque(kPlate, static_cast<btScalar>(roll_torque));
        table.IntegrateForces(dt_);
        table.ServoImpulse(kCarriage, linear_rate);
    }

private:
    [[nodiscard]] btVector3 RollPivot(const TableBody& table) const {
        return table.LinkTransform(kYoke) * pitch_to_roll_;
    }
    [[nodiscard]] double Spring(double inertia, double error, double error_rate) const {
        return inertia * (wn_ * wn_ * error + 2.0 * zeta_ * wn_ * error_rate);
    }

    btVector3 pitch_to_roll_;
    double dt_;
    bool compliant_;
    double wn_;
    double zeta_;
    double pitch_inertia_ = 0.0;
    double roll_inertia_ = 0.0;
};

}  // namespace

TableRun RunTable(const TableConfig& config, Motion motion) {
    config.Validate();
    TableRun run;
    run.schedule = PlanCarriage(config, motion);
    const TableGeometry geometry = GeometryOf(config);
    const AngleProfile roll = RollCommand(config, motion);
    const AngleProfile pitch = PitchCommand(config, motion);
    const double dt = 1.0 / config.physics_rate_hz;
    const auto steps = static_cast<long>(std::ceil(run.schedule.Duration() / dt - 1e-9));

    const Commands start = CommandAt(run.schedule, roll, pitch, 0.0);
    TableBody table(geometry, start.value, start.rate);
    Drive drive(table, config, geometry);

    const auto samples_expected = static_cast<std::size_t>(steps / config.output_decimation + 2);
    std::vector<core::TimedPose> samples;
    samples.reserve(samples_expected);
    run.joints.reserve(samples_expected);
    run.rates.reserve(samples_expected);
    TableJoints q;
    TableJoints q_rate;
    MeasureJoints(table.body(), q, q_rate);
    const auto record = [&](double t_s) {
        samples.push_back({t_s, FromBt(table.LinkTransform(kPlate))});
        run.joints.push_back(q);
        run.rates.push_back(q_rate);
    };
    record(0.0);
    for (long k = 0; k < steps; ++k) {
        const double t_next = static_cast<double>(k + 1) / config.physics_rate_hz;
        drive.Step(table, CommandAt(run.schedule, roll, pitch, t_next), q, q_rate);
        table.body().stepPositionsMultiDof(static_cast<btScalar>(dt));
        table.UpdateTransforms();
        MeasureJoints(table.body(), q, q_rate);
        if ((k + 1) % config.output_decimation == 0 || k + 1 == steps) {
            record(t_next);
        }
    }
    run.trajectory = core::Trajectory(std::move(samples));
    return run;
}

core::Trajectory SimulateTable(const TableConfig& config, Motion motion) {
    return RunTable(config, motion).trajectory;
}

}  // namespace casmap::rig
