#!/bin/sh
# What the installed libluz exports: the renderer, and nothing of the lab,
# io, the command line or the viewer. Every exported function and variable
# is named luz_*.
#
# Usage: exports.sh LIBLUZ_SO
set -u
library=$1
if ! command -v nm >/dev/null 2>&1; then
    echo "exports: nm (binutils) is not installed"
    exit 77
fi
symbols=$(nm -D --defined-only "$library" | awk '$2 ~ /^[TDBRVW]$/ { print $3 }' | sort)
if [ -z "$symbols" ]; then
    echo "exports: $library exports nothing"
    exit 1
fi
status=0
for symbol in $symbols; do
    case $symbol in
    _init|_fini|_edata|_end|__bss_start) continue ;;
    luz_options_*|luz_panel_*|luz_layer_*|luz_overlay_*|luz_hud_*|luz_help_*|luz_slider_*|\
    luz_controls_*|luz_camera_move|luz_camera_turn|luz_camera_reset|luz_spot_*|luz_step_*|\
    luz_bench*|luz_median|luz_wall_ms|luz_cpu_ms|luz_scene_*|luz_cube_*|luz_texture_load|\
    luz_texture_set_*|luz_png_*|luz_framebuffer_write_*|luz_default_textures_directory|\
    luz_new_file_*)
        echo "exports: $symbol belongs to the lab, io or the programs, not to libluz"
        status=1 ;;
    luz_*) ;;
    *)
        echo "exports: $symbol is not named luz_*"
        status=1 ;;
    esac
done
[ "$status" -eq 0 ] && echo "exports: $(echo "$symbols" | wc -l) symbols, all the renderer's"
exit "$status"
