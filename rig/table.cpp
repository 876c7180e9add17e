// rig::Table in Bullet: rigid bodies joined by a slider and two hinges, driven by joint motors.
#include "casmap/rig/table.hpp"

#include <btBulletDynamicsCommon.h>

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
// Rigid motors: far above any torque the motion needs, so they track the command exactly.
constexpr double kMaxMotorForceN = 1e5;
constexpr double kMaxMotorTorqueNm = 1e4;

btVector3 ToBt(const Eigen::Vector3d& v) {
    return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
            static_cast<btScalar>(v.z())};
}

Eigen::Vector3d FromBt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

btTransform ToBt(const core::Pose& pose) {
    const Eigen::Quaterniond& q = pose.rotation;
    return btTransform(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                    static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                       ToBt(pose.translation));
}

core::Pose FromBt(const btTransform& t) {
    const btQuaternion q = t.getRotation();
    return core::Pose{FromBt(t.getOrigin()),
                      Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized()};
}

Eigen::Matrix3d Basis(const btTransform& t) {
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            m(r, c) = t.getBasis()[r][c];
        }
    }
    return m;
}

btTransform Frame(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis, double angle_rad) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(angle_rad, axis));
    return ToBt(core::Pose{origin, q});
}

/// Bullet world and bodies; removes everything from the world before freeing it.
class TableBodies {
public:
    TableBodies(const TableGeometry& geometry, const TableJoints& start) {
        world_.setGravity(btVector3(0, 0, static_cast<btScalar>(-kGravity)));
        world_.getSolverInfo().m_numIterations =
            20;  // keeps the joint frames within microns (Eq. 2 test)
        const core::Pose carriage{
            geometry.pitch_axis_origin_m + Eigen::Vector3d(start.linear_m, 0.0, 0.0),
            Eigen::Quaterniond::Identity()};
        const core::Pose yoke{
            carriage.translation,
            Eigen::Quaterniond(Eigen::AngleAxisd(start.pitch_rad, Eigen::Vector3d::UnitY()))};
        // The plate's centre of mass is the scanner origin: its frame is the sensor frame.
        const core::Pose plate = TableForwardKinematics(geometry, start);
        carriage_ = AddBody(carriage_shape_, kCarriageKg, carriage);
        yoke_ = AddBody(yoke_shape_, kYokeKg, yoke);
        plate_ = AddBody(plate_shape_, kPlateKg, plate);

        slider_ =
            std::make_unique<btSliderConstraint>(*carriage_, btTransform::getIdentity(), true);
        slider_->setPoweredLinMotor(true);
        slider_->setMaxLinMotorForce(static_cast<btScalar>(kMaxMotorForceN));
        // Hinge axes are the frames' z: pitch about y (Rx(-90) maps z to y), roll about x
        // (Ry(90) maps z to x), both at zero joint angle.
        const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
        pitch_ = std::make_unique<btHingeConstraint>(
            *carriage_, *yoke_, Frame(zero, Eigen::Vector3d::UnitX(), -std::numbers::pi / 2),
            Frame(zero, Eigen::Vector3d::UnitX(), -std::numbers::pi / 2));
        roll_ = std::make_unique<btHingeConstraint>(
            *yoke_, *plate_,
            Frame(geometry.pitch_to_roll_m, Eigen::Vector3d::UnitY(), std::numbers::pi / 2),
            Frame(Eigen::Vector3d(0.0, 0.0, -geometry.roll_to_sensor_m), Eigen::Vector3d::UnitY(),
                  std::numbers::pi / 2));
        world_.addConstraint(slider_.get(), true);
        world_.addConstraint(pitch_.get(), true);
        world_.addConstraint(roll_.get(), true);
    }

    ~TableBodies() {
        world_.removeConstraint(roll_.get());
        world_.removeConstraint(pitch_.get());
        world_.removeConstraint(slider_.get());
        for (btRigidBody* body : {plate_.get(), yoke_.get(), carriage_.get()}) {
            world_.removeRigidBody(body);
        }
    }
    TableBodies(const TableBodies&) = delete;
    TableBodies& operator=(const TableBodies&) = delete;

    btDiscreteDynamicsWorld& world() { return world_; }
    btRigidBody& carriage() { return *carriage_; }
    btRigidBody& yoke() { return *yoke_; }
    btRigidBody& plate() { return *plate_; }
    btSliderConstraint& slider() { return *slider_; }
    btHingeConstraint& pitch() { return *pitch_; }
    btHingeConstraint& roll() { return *roll_; }

private:
    std::unique_ptr<btRigidBody> AddBody(btCollisionShape& shape,
                                         double mass_kg,
                                         const core::Pose& pose) {
        btVector3 inertia(0, 0, 0);
        shape.calculateLocalInertia(static_cast<btScalar>(mass_kg), inertia);
        btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass_kg), nullptr,
                                                      &shape, inertia);
        info.m_startWorldTransform = ToBt(pose);
        auto body = std::make_unique<btRigidBody>(info);
        body->setActivationState(DISABLE_DEACTIVATION);
        body->setDamping(0, 0);
        // The table's parts never collide with anything: group 1, mask 0.
        world_.addRigidBody(body.get(), 1, 0);
        return body;
    }

    btDefaultCollisionConfiguration collision_config_;
    btCollisionDispatcher dispatcher_{&collision_config_};
    btDbvtBroadphase broadphase_;
    btSequentialImpulseConstraintSolver solver_;
    btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &collision_config_};
    btBoxShape carriage_shape_{btVector3(0.20F, 0.15F, 0.05F)};
    btBoxShape yoke_shape_{btVector3(0.10F, 0.10F, 0.10F)};
    btBoxShape plate_shape_{btVector3(0.08F, 0.08F, 0.09F)};
    std::unique_ptr<btRigidBody> carriage_;
    std::unique_ptr<btRigidBody> yoke_;
    std::unique_ptr<btRigidBody> plate_;
    std::unique_ptr<btSliderConstraint> slider_;
    std::unique_ptr<btHingeConstraint> pitch_;
    std::unique_ptr<btHingeConstraint> roll_;
};

/// Joint values and rates read from the bodies (not from Bullet's constraint bookkeeping).
void MeasureJoints(TableBodies& bodies,
                   const TableGeometry& geometry,
                   TableJoints& value,
                   TableJoints& rate) {
    const btTransform& c = bodies.carriage().getCenterOfMassTransform();
    const btTransform& y = bodies.yoke().getCenterOfMassTransform();
    const btTransform& p = bodies.plate().getCenterOfMassTransform();
    const Eigen::Matrix3d rc = Basis(c);
    const Eigen::Matrix3d ry = Basis(y);
    const Eigen::Matrix3d pitch_rel = rc.transpose() * ry;       // Ry(pitch)
    const Eigen::Matrix3d roll_rel = ry.transpose() * Basis(p);  // Rx(roll)
    value.linear_m = c.getOrigin().x() - geometry.pitch_axis_origin_m.x();
    value.pitch_rad = std::atan2(pitch_rel(0, 2), pitch_rel(0, 0));
    value.roll_rad = std::atan2(roll_rel(2, 1), roll_rel(1, 1));
    const Eigen::Vector3d wc = FromBt(bodies.carriage().getAngularVelocity());
    const Eigen::Vector3d wy = FromBt(bodies.yoke().getAngularVelocity());
    const Eigen::Vector3d wp = FromBt(bodies.plate().getAngularVelocity());
    rate.linear_m = bodies.carriage().getLinearVelocity().x();
    rate.pitch_rad = (wy - wc).dot(rc.col(1));
    rate.roll_rad = (wp - wy).dot(ry.col(0));
}

/// Gives every body the velocity of the commanded joint rates at the start.
void SetStartVelocities(TableBodies& bodies, const TableJoints& rate) {
    const btVector3 v(static_cast<btScalar>(rate.linear_m), 0, 0);
    const btVector3 pivot = bodies.yoke().getCenterOfMassPosition();
    const btVector3 w_pitch = btVector3(0, static_cast<btScalar>(rate.pitch_rad), 0);
    const btVector3 roll_axis = bodies.yoke().getCenterOfMassTransform().getBasis().getColumn(0);
    const btVector3 w_plate = w_pitch + roll_axis * static_cast<btScalar>(rate.roll_rad);
    const btVector3 roll_pivot =
        bodies.yoke().getCenterOfMassTransform() * bodies.roll().getAFrame().getOrigin();
    const btVector3 plate_pos = bodies.plate().getCenterOfMassPosition();
    const btVector3 v_roll_pivot = v + w_pitch.cross(roll_pivot - pivot);
    bodies.carriage().setLinearVelocity(v);
    bodies.yoke().setLinearVelocity(v);
    bodies.yoke().setAngularVelocity(w_pitch);
    bodies.plate().setLinearVelocity(v_roll_pivot + w_plate.cross(plate_pos - roll_pivot));
    bodies.plate().setAngularVelocity(w_plate);
}

/// Moment of inertia (kg m^2) of `body` about the axis through `pivot` along unit `axis`.
double InertiaAbout(const btRigidBody& body, const btVector3& pivot, const btVector3& axis) {
    const btVector3 local_axis = body.getCenterOfMassTransform().getBasis().transpose() * axis;
    const btVector3 inv_local = body.getInvInertiaDiagLocal();
    double i_axis = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double inv = inv_local[k];
        i_axis += inv > 0.0 ? local_axis[k] * local_axis[k] / inv : 0.0;
    }
    const double lever = (body.getCenterOfMassPosition() - pivot).cross(axis).length();
    return i_axis + lever * lever / body.getInvMass();
}

/// Gravity torque (N m) about the axis through `pivot` of the bodies in `distal`.
double GravityTorque(std::initializer_list<const btRigidBody*> distal,
                     const btVector3& pivot,
                     const btVector3& axis) {
    double torque = 0.0;
    for (const btRigidBody* body : distal) {
        const btVector3 weight(0, 0, static_cast<btScalar>(-kGravity / body->getInvMass()));
        torque += (body->getCenterOfMassPosition() - pivot).cross(weight).dot(axis);
    }
    return torque;
}

/// Spring-damper torque about a hinge, applied equal and opposite to its two bodies.
void ApplyJointTorque(btRigidBody& a, btRigidBody& b, const btVector3& axis, double torque_nm) {
    const btVector3 t = axis * static_cast<btScalar>(torque_nm);
    b.applyTorque(t);
    a.applyTorque(-t);
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

/// The rotary joints' drive: rigid dead-beat motors, or the compliant spring-damper servo.
class RotaryDrive {
public:
    RotaryDrive(TableBodies& bodies, const TableConfig& config)
        : dt_(1.0 / config.physics_rate_hz),
          compliant_(config.compliance.enabled),
          wn_(2.0 * std::numbers::pi * config.compliance.natural_frequency_hz),
          zeta_(config.compliance.damping_ratio) {
        // Inertias of the distal bodies about each axis, taken at the start pose.
        const btTransform& yoke = bodies.yoke().getCenterOfMassTransform();
        const btVector3 pitch_pivot = yoke.getOrigin();
        const btVector3 pitch_axis(0, 1, 0);
        pitch_inertia_ = InertiaAbout(bodies.yoke(), pitch_pivot, pitch_axis) +
                         InertiaAbout(bodies.plate(), pitch_pivot, pitch_axis);
        roll_inertia_ = InertiaAbout(bodies.plate(), yoke * bodies.roll().getAFrame().getOrigin(),
                                     yoke.getBasis().getColumn(0));
        if (compliant_) {
            bodies.pitch().enableMotor(false);
            bodies.roll().enableMotor(false);
        }
    }

    void Apply(TableBodies& bodies,
               const Commands& cmd,
               const TableJoints& q,
               const TableJoints& q_rate) const {
        if (!compliant_) {
            // Bullet's hinge motor velocity is that of body A relative to B about the axis:
            // the opposite sign of our joint rate (B relative to A).
            const auto max_impulse = static_cast<btScalar>(kMaxMotorTorqueNm * dt_);
            bodies.pitch().enableAngularMotor(
                true, static_cast<btScalar>(-(cmd.value.pitch_rad - q.pitch_rad) / dt_),
                max_impulse);
            bodies.roll().enableAngularMotor(
                true, static_cast<btScalar>(-(cmd.value.roll_rad - q.roll_rad) / dt_), max_impulse);
            return;
        }
        // Spring-damper servo with gravity feed-forward (a real drive's integral action), so
        // the table rings about its command instead of sagging.
        const btTransform& yoke = bodies.yoke().getCenterOfMassTransform();
        const btVector3 roll_axis = yoke.getBasis().getColumn(0);
        const btVector3 roll_pivot = yoke * bodies.roll().getAFrame().getOrigin();
        const btVector3 pitch_axis =
            bodies.carriage().getCenterOfMassTransform().getBasis().getColumn(1);
        const double pitch_torque =
            Spring(pitch_inertia_, cmd.value.pitch_rad - q.pitch_rad,
                   cmd.rate.pitch_rad - q_rate.pitch_rad) -
            GravityTorque({&bodies.yoke(), &bodies.plate()}, yoke.getOrigin(), pitch_axis);
        const double roll_torque = Spring(roll_inertia_, cmd.value.roll_rad - q.roll_rad,
                                          cmd.rate.roll_rad - q_rate.roll_rad) -
                                   GravityTorque({&bodies.plate()}, roll_pivot, roll_axis);
        ApplyJointTorque(bodies.carriage(), bodies.yoke(), pitch_axis, pitch_torque);
        ApplyJointTorque(bodies.yoke(), bodies.plate(), roll_axis, roll_torque);
    }

private:
    [[nodiscard]] double Spring(double inertia, double error, double error_rate) const {
        return inertia * (wn_ * wn_ * error + 2.0 * zeta_ * wn_ * error_rate);
    }

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
    TableBodies bodies(geometry, start.value);
    SetStartVelocities(bodies, start.rate);
    const RotaryDrive drive(bodies, config);

    std::vector<core::TimedPose> samples;
    samples.reserve(static_cast<std::size_t>(steps / config.output_decimation + 1));
    TableJoints q;
    TableJoints q_rate;
    const auto record = [&](double t_s) {
        MeasureJoints(bodies, geometry, q, q_rate);
        samples.push_back({t_s, FromBt(bodies.plate().getCenterOfMassTransform())});
        run.joints.push_back(q);
        run.rates.push_back(q_rate);
    };
    record(0.0);
    for (long k = 0; k < steps; ++k) {
        const double t_next = static_cast<double>(k + 1) / config.physics_rate_hz;
        const Commands cmd = CommandAt(run.schedule, roll, pitch, t_next);
        MeasureJoints(bodies, geometry, q, q_rate);
        // Dead-beat velocity servo: the motor velocity that lands on the command next step.
        bodies.slider().setTargetLinMotorVelocity(
            static_cast<btScalar>((cmd.value.linear_m - q.linear_m) / dt));
        drive.Apply(bodies, cmd, q, q_rate);
        bodies.world().stepSimulation(static_cast<btScalar>(dt), 0, static_cast<btScalar>(dt));
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
