"""The old import path of the engines and of the host's plan of a view, kept for its
remaining callers (the testbenches in tb/, cube4_reports.scenes): the engines and images
are ``cube4.app.render``, the plan is the specification's ``cube4.host``. This module is
part of the application (``cube4.APPLICATION``); new code imports those two modules."""

from __future__ import annotations

from .app.render import (Engine, RenderResult, engine_names, register_engine, render, render_bricked_views,  # noqa: F401
                         render_golden_view, render_reference_view, render_views, scene_warp, view_image,
                         warp_to_image)
from .host import (ViewPlan, assemble_view, build_memory, config_for, crop_volume, frame_clip, golden_view,  # noqa: F401
                   host_tables, image_metrics, memory_volume, pass_rects, plan_view, schedule_stats, schedules,
                   setup_view, trav_stats, view_stats)
