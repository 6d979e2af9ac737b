# Sourced with a scale (smoke|default|paper): defines excluded_args OMEGA,
# which prints the `hgrid generate` options that make an excluded-volume
# packing as experiments/fig11.toml does at that size ratio (omega <= 10:
# compression; above: sequential addition; then event chains with swaps
# until T/N is stationary within 0.25 %, at most 1000 sweeps, 20 at the
# smoke scale), so that the scripts drawing single packings reuse the
# scene's cached ones. experiments/occupancy.toml makes omega = 100 the same
# way. Keep them in step.
case "${1:-default}" in smoke) fig_sweeps=20 ;; *) fig_sweeps=1000 ;; esac
excluded_args() {
  local method=auto
  if awk -v w="$1" 'BEGIN { exit !(w <= 10) }'; then method=growth; fi
  echo "--method $method --equilibrate --moves event-chain --sweeps $fig_sweeps --stop stationary --stationary-tol 0.0025"
}
