// The walk's wall neighbours (walk_walls.wgsl), visited by every kernel but those
// built with `walls_if;`, which name their own condition.

fn walk_walls() -> bool {
    return true;
}
