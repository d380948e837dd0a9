// demo:whitted (src/scene/demo_scenes.cpp) for POV-Ray 3.7, for bench/whitted_vs_povray.sh:
// same camera, floor, spheres, lights, background and ray depth, so the work per ray compares.
// POV-Ray is left-handed: every z is mirrored (z -> -z), which keeps x to the right and y up.
// Render with File_Gamma=1.0 to get luz's linear 8-bit encoding (PSNR ~42 dB against luz).
#version 3.7;

global_settings {
    assumed_gamma 1.0
    // luz's max_depth 5 = POV-Ray's max_trace_level 5: with both, the reflected and refracted
    // ray counts agree to a few rays in 10^5 (POV-Ray's statistics against luz's --stats).
    max_trace_level 5
    // luz never prunes a ray by its weight; POV-Ray's default 1/255 would drop the deep
    // glass branches (0.1 x 0.1 x ...), so switch it off to trace the same tree.
    adc_bailout 0
    ambient_light rgb 1  // Ia = 1
}

// luz: position [0, 1.7, 7], look_at [0, 0.9, 0], up +y, fov_y 40 at W/H = 4/3.
// POV-Ray's angle is horizontal: 2·atan(tan(40°/2)·4/3) = 51.774°.
camera {
    perspective
    location <0, 1.7, -7>
    look_at <0, 0.9, 0>
    sky y
    up y
    right x * image_width / image_height
    angle 51.774
}

background { rgb <0.35, 0.55, 0.85> }

// luz's Il/(d + K) with K = 1: POV-Ray attenuates by 2 / (1 + (d/fade_distance)^fade_power),
// so fade_distance 1, fade_power 1 and a colour of Il/2 give exactly Il/(1 + d).
light_source { <-4, 6, -5> rgb 7 / 2 fade_distance 1 fade_power 1 }
light_source { <5, 4, -2> rgb 2.5 / 2 fade_distance 1 fade_power 1 }

// Floor: plane y = 0, checker of cell 1; yellow Kd (0.85, 0.75, 0.15), red Kd (0.8, 0.12, 0.08),
// Ka ≈ 0.12·Kd, Ks 0. The checker is mirrored back (scale z -1) so the cells fall as in luz.
plane {
    y, 0
    pigment {
        checker rgb <0.8, 0.12, 0.08>, rgb <0.85, 0.75, 0.15>
        scale <1, 1, -1>
    }
    finish { ambient 0.12 diffuse 1 }
}

// Mirror: metal_polido with reflection 0.8: Kd (0.15, 0.15, 0.16), Ka 0.2·Kd, Ks 0.9, n 200.
sphere {
    <-0.9, 1.0, 1.0>, 1.0
    pigment { rgb <0.15, 0.15, 0.16> }
    finish { ambient 0.2 diffuse 1 phong 0.9 phong_size 200 reflection 0.8 }
}

// Glass: vidro: Kd 0.02, Ka 0.2·Kd, Ks 0.9, n 500, reflection 0.1, transparency 0.9, ior 1.5.
sphere {
    <0.9, 0.75, -1.0>, 0.75
    pigment { rgbt <0.02, 0.02, 0.02, 0.9> }
    finish { ambient 0.2 diffuse 1 phong 0.9 phong_size 500 reflection 0.1 }
    interior { ior 1.5 }
}
