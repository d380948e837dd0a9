// Camera conventions of docs/SCENES.md#geometry: basis, pixel centres, view_height and fov_y.
#include "scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace luz {
namespace {

void expect_vec(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

CameraDesc looking_down_minus_z() {
    CameraDesc d;
    d.position = {0, 0, 10};
    d.look_at = {0, 0, 0};
    d.up = {0, 1, 0};
    return d;
}

TEST(Camera, BasisIsRightHandedWithWTowardsTheViewer) {
    CameraDesc d;
    d.position = {3, 4, 5};
    d.look_at = {0, 1, 0};
    const Camera c = Camera::from(d, 100, 50);
    expect_vec(c.w, normalize(Vec3{3, 3, 5}));
    expect_vec(c.u, normalize(cross(d.up, c.w)));
    expect_vec(c.v, cross(c.w, c.u));
    EXPECT_NEAR(dot(c.u, c.v), 0, 1e-6f);
}

TEST(Camera, OrthographicPixelCentresAndViewHeight) {
    CameraDesc d = looking_down_minus_z();
    d.view_height = 4;
    const Camera c = Camera::from(d, 200, 100);  // aspect 2: view width 8
    // Pixel (0, 0) has its centre at (0.5, 0.5): x = 2·0.5/200 − 1, y = 1 − 2·0.5/100.
    const Ray r = c.ray(0.5f, 0.5f);
    expect_vec(r.direction, {0, 0, -1});
    expect_vec(r.origin, {(2 * 0.5f / 200 - 1) * 4.0f, (1 - 2 * 0.5f / 100) * 2.0f, 10});
    // The image's edges are at ±view_height/2 vertically, ±view_height·W/H/2 horizontally.
    expect_vec(c.ray(100, 0).origin, {0, 2, 10});
    expect_vec(c.ray(200, 50).origin, {4, 0, 10});
    expect_vec(c.ray(0, 100).origin, {-4, -2, 10});
}

TEST(Camera, PerspectiveFovIsTheVerticalAngle) {
    CameraDesc d = looking_down_minus_z();
    d.projection = Projection::perspective;
    d.fov_y = 60;
    const Camera c = Camera::from(d, 300, 100);
    const Ray top = c.ray(150, 0);
    expect_vec(top.origin, d.position);
    const float half_angle = std::acos(dot(top.direction, Vec3{0, 0, -1}));
    EXPECT_NEAR(half_angle * 180 / std::numbers::pi_v<float>, 30.0f, 1e-3f);
    EXPECT_GT(top.direction.y, 0);
    // Horizontally the image plane is W/H times wider: tan(half_x) = 3·tan(30°).
    const Ray right = c.ray(300, 50);
    EXPECT_NEAR(right.direction.x / -right.direction.z, 3 * std::tan(std::numbers::pi / 6), 1e-5);
    EXPECT_NEAR(length(right.direction), 1.0f, 1e-6f);
}

TEST(Camera, ToViewGivesDepthInFrontOfTheCameraPlane) {
    const Camera c = Camera::from(looking_down_minus_z(), 10, 10);
    expect_vec(c.to_view({1, 2, 3}), {1, 2, 7});
    EXPECT_LT(c.to_view({0, 0, 11}).z, 0);
}

}  // namespace
}  // namespace luz
