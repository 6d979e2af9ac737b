# Sourced with a scale (smoke|default|paper): sets excluded_args, the `hgrid
# generate` options that make an excluded-volume packing as
# experiments/fig11.toml and fig12.toml do (compression, then Monte Carlo with
# swaps until T/N is stationary, at most 1000 sweeps, 20 at the smoke scale),
# so that the scripts drawing single packings reuse the scenes' cached ones.
# Keep the two in step.
case "${1:-default}" in smoke) fig_sweeps=20 ;; *) fig_sweeps=1000 ;; esac
excluded_args="--method growth --equilibrate --sweeps $fig_sweeps --stop stationary"
