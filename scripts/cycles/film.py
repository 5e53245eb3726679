"""Cycles render settings shared by the comparison scripts in this folder: a linear float EXR
film at 100 % of the given size, square pixels, no border, transparency, compositing or
sequencer, the Standard view transform with no look (so pixels stay the scene's radiance), a
fixed thread count, CPU, and no adaptive sampling. The caller sets samples, time limit, bounces
and the pixel filter.
"""


def linear_exr_film(scene, width, height, threads):
    """Applies the settings above to `scene` (bpy.types.Scene); returns scene.cycles."""
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.use_border = False
    r.film_transparent = False
    r.threads_mode = "FIXED"
    r.threads = threads
    r.use_compositing = False
    r.use_sequencer = False
    r.use_persistent_data = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_mode = "RGB"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "ZIP"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0

    c = scene.cycles
    c.device = "CPU"
    if hasattr(c, "feature_set"):
        c.feature_set = "SUPPORTED"
    c.use_adaptive_sampling = False
    return c
