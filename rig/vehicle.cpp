// rig::Vehicle in Bullet: btRaycastVehicle on the scene's terrain, speed and line controllers.
#include "casmap/rig/vehicle.hpp"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <variant>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::rig {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kGravity = 9.81;
constexpr double kWheelGap = 0.01;       // suspension mounts just below the chassis box (m)
constexpr double kSettleBrake = 1000.0;  // brake impulse while settling (N s)
constexpr double kMaxSteerRad = 0.35;
constexpr double kSteerPerMetre = 1.0;  // line controller: rad per metre off the line
constexpr double kSteerPerRad = 2.0;    // ... and per rad of heading error

btVector3 ToBt(const Eigen::Vector3d& v) {
    return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
            static_cast<btScalar>(v.z())};
}

btTransform ToBt(const core::Pose& pose) {
    const Eigen::Quaterniond& q = pose.rotation;
    return btTransform(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                    static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                       ToBt(pose.translation));
}

core::Pose FromBt(const btTransform& t) {
    const btQuaternion q = t.getRotation();
    return core::Pose{Eigen::Vector3d(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z()),
                      Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized()};
}

/// Static terrain bodies built from the scene's `terrain: true` objects.
class Terrain {
public:
    Terrain(const core::Scene& scene, btDiscreteDynamicsWorld& world) : world_(world) {
        for (std::size_t i = 0; i < scene.objects.size(); ++i) {
            const core::SceneObject& object = scene.objects[i];
            if (object.terrain) {
                Add(std::visit([&](const auto& shape) { return MakeShape(shape, scene, i); },
                               object.shape),
                    object.world_T_object);
            }
        }
        if (bodies_.empty()) {
            throw MakeInputError(scene.source_path.empty() ? "scene" : scene.source_path,
                                 "objects[].terrain", "",
                                 "the vehicle needs at least one object with terrain: true");
        }
    }
    ~Terrain() {
        for (const auto& body : bodies_) {
            world_.removeRigidBody(body.get());
        }
    }
    Terrain(const Terrain&) = delete;
    Terrain& operator=(const Terrain&) = delete;

private:
    std::unique_ptr<btCollisionShape> MakeShape(const core::BoxShape& box,
                                                const core::Scene& /*scene*/,
                                                std::size_t /*index*/) {
        return std::make_unique<btBoxShape>(ToBt(0.5 * box.size_m));
    }
    std::unique_ptr<btCollisionShape> MakeShape(const core::CylinderShape& cylinder,
                                                const core::Scene& /*scene*/,
                                                std::size_t /*index*/) {
        const auto r = static_cast<btScalar>(cylinder.radius_m);
        return std::make_unique<btCylinderShapeZ>(
            btVector3(r, r, static_cast<btScalar>(0.5 * cylinder.height_m)));
    }
    std::unique_ptr<btCollisionShape> MakeShape(const core::MeshShape& mesh,
                                                const core::Scene& scene,
                                                std::size_t index) {
        if (mesh.triangles.empty()) {
            throw MakeInputError(scene.source_path.empty() ? "scene" : scene.source_path,
                                 "objects[" + std::to_string(index) + "].mesh", mesh.source_path,
                                 "a terrain mesh needs at least one triangle");
        }
        auto triangles = std::make_unique<btTriangleMesh>(true, false);
        const auto vertex = [&](int k) {
            const Eigen::Vector3f& v = mesh.vertices[static_cast<std::size_t>(k)];
            return btVector3(v.x(), v.y(), v.z());
        };
        for (const Eigen::Vector3i& t : mesh.triangles) {
            triangles->addTriangle(vertex(t.x()), vertex(t.y()), vertex(t.z()), false);
        }
        auto shape = std::make_unique<btBvhTriangleMeshShape>(triangles.get(), true);
        meshes_.push_back(std::move(triangles));
        return shape;
    }
    void Add(std::unique_ptr<btCollisionShape> shape, const core::Pose& pose) {
        btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shape.get());
        info.m_startWorldTransform = ToBt(pose);
        info.m_friction = 1.0;
        auto body = std::make_unique<btRigidBody>(info);
        world_.addRigidBody(body.get());
        shapes_.push_back(std::move(shape));
        bodies_.push_back(std::move(body));
    }

    btDiscreteDynamicsWorld& world_;
    std::vector<std::unique_ptr<btTriangleMesh>> meshes_;
    std::vector<std::unique_ptr<btCollisionShape>> shapes_;
    std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

/// Highest terrain point below (x, y), or nullopt if there is none.
std::optional<double> GroundZ(btDiscreteDynamicsWorld& world, double x, double y) {
    const auto bx = static_cast<btScalar>(x);
    const auto by = static_cast<btScalar>(y);
    const btVector3 from(bx, by, 1000.0F);
    const btVector3 to(bx, by, -1000.0F);
    btCollisionWorld::ClosestRayResultCallback hit(from, to);
    world.rayTest(from, to, hit);
    if (!hit.hasHit()) {
        return std::nullopt;
    }
    return static_cast<double>(hit.m_hitPointWorld.z());
}

/// Bullet world, terrain, chassis and raycast vehicle; torn down in the right order.
class VehicleWorld {
public:
    VehicleWorld(const core::Scene& scene, const VehicleConfig& c) : terrain_(scene, world_) {
        world_.setGravity(btVector3(0, 0, static_cast<btScalar>(-kGravity)));
        const Eigen::Vector3d half = 0.5 * c.chassis_size_m;
        const double hx = 0.5 * c.wheelbase_m;
        const double hy = 0.5 * c.track_m;
        double ground = -std::numeric_limits<double>::infinity();
        for (const auto& [dx, dy] :
             {std::pair{0.0, 0.0}, {hx, hy}, {hx, -hy}, {-hx, hy}, {-hx, -hy}}) {
            const auto z = GroundZ(world_, c.start_xy_m.x() + dx, c.start_xy_m.y() + dy);
            ground = z ? std::max(ground, *z) : ground;
        }
        if (!std::isfinite(ground)) {
            throw MakeInputError(
                "vehicle config", "vehicle.start_xy_m",
                core::FormatNumber(c.start_xy_m.x()) + ", " + core::FormatNumber(c.start_xy_m.y()),
                "no terrain below the start position");
        }
        const double drop = 0.02;  // spawn slightly above full extension, then settle
        const double z0 =
            ground + c.wheel_radius_m + c.suspension_rest_m + kWheelGap + half.z() + drop;
        chassis_shape_ = std::make_unique<btBoxShape>(ToBt(half));
        btVector3 inertia(0, 0, 0);
        const auto mass = static_cast<btScalar>(c.chassis_mass_kg);
        chassis_shape_->calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, chassis_shape_.get(), inertia);
        info.m_startWorldTransform =
            ToBt(core::Pose{Eigen::Vector3d(c.start_xy_m.x(), c.start_xy_m.y(), z0),
                            Eigen::Quaterniond::Identity()});
        chassis_ = std::make_unique<btRigidBody>(info);
        chassis_->setActivationState(DISABLE_DEACTIVATION);
        world_.addRigidBody(chassis_.get());

        btRaycastVehicle::btVehicleTuning tuning;
        tuning.m_suspensionStiffness = static_cast<btScalar>(c.suspension_stiffness);
        tuning.m_suspensionCompression = static_cast<btScalar>(c.suspension_compression);
        tuning.m_suspensionDamping = static_cast<btScalar>(c.suspension_relaxation);
        tuning.m_maxSuspensionTravelCm = static_cast<btScalar>(100.0 * c.suspension_travel_m);
        tuning.m_frictionSlip = static_cast<btScalar>(c.wheel_friction);
        tuning.m_maxSuspensionForce = static_cast<btScalar>(1e6);
        raycaster_ = std::make_unique<btDefaultVehicleRaycaster>(&world_);
        vehicle_ = std::make_unique<btRaycastVehicle>(tuning, chassis_.get(), raycaster_.get());
        vehicle_->setCoordinateSystem(1, 2, 0);  // right = y, up = z, forward = x
        world_.addAction(vehicle_.get());
        // Axle along -y: Bullet drives along axle x normal, i.e. +x on flat ground.
        const btVector3 down(0, 0, -1);
        const btVector3 axle(0, -1, 0);
        const double mount_z = -half.z() - kWheelGap;
        for (const auto& [dx, dy] : {std::pair{hx, hy}, {hx, -hy}, {-hx, hy}, {-hx, -hy}}) {
            btWheelInfo& wheel =
                vehicle_->addWheel(ToBt(Eigen::Vector3d(dx, dy, mount_z)), down, axle,
                                   static_cast<btScalar>(c.suspension_rest_m),
                                   static_cast<btScalar>(c.wheel_radius_m), tuning, dx > 0.0);
            wheel.m_rollInfluence = 1.0F;  // no anti-roll trick: real roll over rough ground
        }
    }
    ~VehicleWorld() {
        world_.removeAction(vehicle_.get());
        world_.removeRigidBody(chassis_.get());
    }
    VehicleWorld(const VehicleWorld&) = delete;
    VehicleWorld& operator=(const VehicleWorld&) = delete;

    btDiscreteDynamicsWorld& world() { return world_; }
    btRaycastVehicle& vehicle() { return *vehicle_; }
    btRigidBody& chassis() { return *chassis_; }

private:
    btDefaultCollisionConfiguration collision_config_;
    btCollisionDispatcher dispatcher_{&collision_config_};
    btDbvtBroadphase broadphase_;
    btSequentialImpulseConstraintSolver solver_;
    btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &collision_config_};
    Terrain terrain_;
    std::unique_ptr<btBoxShape> chassis_shape_;
    std::unique_ptr<btRigidBody> chassis_;
    std::unique_ptr<btDefaultVehicleRaycaster> raycaster_;
    std::unique_ptr<btRaycastVehicle> vehicle_;
};

void SetDrive(btRaycastVehicle& vehicle, double force_n, double brake, double steer_rad) {
    for (int i = 0; i < vehicle.getNumWheels(); ++i) {
        vehicle.applyEngineForce(static_cast<btScalar>(0.25 * force_n), i);
        vehicle.setBrake(static_cast<btScalar>(brake), i);
        vehicle.setSteeringValue(
            static_cast<btScalar>(vehicle.getWheelInfo(i).m_bIsFrontWheel ? steer_rad : 0.0), i);
    }
}

int WheelsInContact(const btRaycastVehicle& vehicle) {
    int n = 0;
    for (int i = 0; i < vehicle.getNumWheels(); ++i) {
        n += vehicle.getWheelInfo(i).m_raycastInfo.m_isInContact ? 1 : 0;
    }
    return n;
}

double ForwardSpeed(const btRigidBody& chassis) {
    const btTransform& t = chassis.getCenterOfMassTransform();
    return static_cast<double>(chassis.getLinearVelocity().dot(t.getBasis().getColumn(0)));
}

/// Speed PI with anti-windup and the ramp's acceleration fed forward.
class SpeedController {
public:
    explicit SpeedController(const VehicleConfig& config) : c_(config) {}

    /// Drive force (N) for the step ending at t_next_s, given the forward speed now.
    double Force(double t_next_s, double speed_m_s) {
        const double v_set = c_.speed_m_s * std::min(1.0, t_next_s / c_.speed_ramp_s);
        const double error = v_set - speed_m_s;
        // Anti-windup: the integral alone never asks for more than the force limit.
        const double i_max =
            c_.speed_ki_n_per_m > 0.0 ? c_.max_drive_force_n / c_.speed_ki_n_per_m : 0.0;
        integral_ = std::clamp(integral_ + error / c_.physics_rate_hz, -i_max, i_max);
        // Feed-forward of the ramp's acceleration, so the PI loop only corrects disturbances.
        const double accel = t_next_s < c_.speed_ramp_s ? c_.speed_m_s / c_.speed_ramp_s : 0.0;
        return std::clamp(c_.chassis_mass_kg * accel + c_.speed_kp_n_per_m_s * error +
                              c_.speed_ki_n_per_m * integral_,
                          -c_.max_drive_force_n, c_.max_drive_force_n);
    }

private:
    const VehicleConfig& c_;
    double integral_ = 0.0;
};

/// Front-wheel steering (rad) that holds the straight line y = line_y heading +x.
double SteerToLine(const btRigidBody& chassis, double line_y) {
    const btTransform& t = chassis.getCenterOfMassTransform();
    const btVector3 heading = t.getBasis().getColumn(0);
    const double yaw = std::atan2(heading.y(), heading.x());
    return std::clamp(kSteerPerMetre * (line_y - t.getOrigin().y()) - kSteerPerRad * yaw,
                      -kMaxSteerRad, kMaxSteerRad);
}

}  // namespace

VehicleRun RunVehicle(const core::Scene& scene, const VehicleConfig& config) {
    config.Validate();
    VehicleWorld sim(scene, config);
    const double dt = 1.0 / config.physics_rate_hz;
    const auto bt_dt = static_cast<btScalar>(dt);
    const core::Pose chassis_T_sensor{
        config.mount_xyz_m, core::QuaternionFromRpy(0.0, config.mount_pitch_deg * kDegToRad, 0.0)};
    const auto settle_steps = static_cast<long>(std::lround(config.settle_s / dt));
    for (long k = 0; k < settle_steps; ++k) {
        SetDrive(sim.vehicle(), 0.0, kSettleBrake, 0.0);
        sim.world().stepSimulation(bt_dt, 0, bt_dt);
    }

    VehicleRun run;
    std::vector<core::TimedPose> samples;
    const double start_z = sim.chassis().getCenterOfMassPosition().z();
    const auto sensor_pose = [&] {
        return FromBt(sim.chassis().getCenterOfMassTransform()) * chassis_T_sensor;
    };
    const auto record = [&](double t_s) {
        samples.push_back({t_s, sensor_pose()});
        run.wheels_in_contact.push_back(WheelsInContact(sim.vehicle()));
        run.speed_m_s.push_back(ForwardSpeed(sim.chassis()));
    };
    record(0.0);
    const double distance = config.end_x_m - samples.front().world_T_sensor.translation.x();
    const double time_limit_s = 3.0 * distance / config.speed_m_s + 2.0 * config.speed_ramp_s + 5.0;
    SpeedController speed(config);
    for (long k = 0;; ++k) {
        const double t_next = static_cast<double>(k + 1) / config.physics_rate_hz;
        SetDrive(sim.vehicle(), speed.Force(t_next, ForwardSpeed(sim.chassis())), 0.0,
                 SteerToLine(sim.chassis(), config.start_xy_m.y()));
        sim.world().stepSimulation(bt_dt, 0, bt_dt);
        const core::Pose sensor = sensor_pose();
        const bool done = sensor.translation.x() >= config.end_x_m;
        if ((k + 1) % config.output_decimation == 0 || done) {
            record(t_next);
        }
        if (done) {
            break;
        }
        if (t_next > time_limit_s || sensor.translation.z() < start_z - 100.0) {
            throw MakeInputError("vehicle config", "vehicle.end_x_m",
                                 core::FormatNumber(config.end_x_m),
                                 "not reached within " + core::FormatNumber(time_limit_s) +
                                     " s: the vehicle is stuck or left the terrain");
        }
    }
    run.trajectory = core::Trajectory(std::move(samples));
    return run;
}

core::Trajectory SimulateVehicle(const core::Scene& scene, const VehicleConfig& config) {
    return RunVehicle(scene, config).trajectory;
}

}  // namespace casmap::rig
