# Sourced by the study scripts: fixed_grid_args UM sets the array
# fixed_args to the overrides of the exact model on the fixed grid with
# elements of UM micrometres (contact.dx), dy = 2.5 dx, the step the element.
fixed_grid_args() {
  local dx
  dx=$(python3 -c "print($1 * 1e-6)")
  fixed_args=(--set contact.model=exact-transient --set contact.grid=fixed --set contact.dx="$dx"
              --set contact.dy="$(python3 -c "print(2.5 * $dx)")" --set passage.step_length="$dx")
}
