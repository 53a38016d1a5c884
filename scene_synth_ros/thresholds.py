"""Every threshold a room is judged by, named for what it measures, in metres and radians.

The validity checks (``geometry``), the robot promise (``rules.robot``), the design rules
(``rules``), insertion (``synth``) and the corpus (``corpus``) read them from here, so that
one name never means two things and a value is changed in one place.
"""
from __future__ import annotations

import math

# ---- validity of a room (``geometry``) ------------------------------------------------
COLLISION_TOLERANCE = 0.01      # first-tier footprints may interpenetrate by at most 1 cm
FLOOR_TOLERANCE = 0.01          # footprints may poke through a wall by at most 1 cm
MIN_SUPPORT = 0.70              # a second-tier footprint must be >= 70 % on its parent
DOOR_ZONE_MIN_DEPTH = 0.80      # clear zone inside a door: at least this deep...
DOOR_ZONE_SIDE_MARGIN = 0.10    # ...and this much wider than the door on each side

# ---- the robot (``rules.robot.Robot``'s defaults) -------------------------------------
# The robot every room is furnished and judged for unless a user names another: it must get
# from every door to every door (the validity check) and reach every object's front.
ROBOT_RADIUS = 0.2
ROBOT_WIDTH = 2 * ROBOT_RADIUS
# The robot reaches an object when its body gets within 0.15 m of it: close enough to look at
# or grasp what is there, without asking for a free corridor wider than the robot.
ROBOT_REACH = 0.15
# A door's clear zone is never shallower than a robot standing just inside it needs
# (``geometry.door_entry_point``, 0.1 m in), whatever a data set's allowance says.
DOOR_ZONE_LEAST_DEPTH = ROBOT_WIDTH + 0.1

# ---- what a layout must be to be furnished (``schema``) --------------------------------
MIN_FLOOR_AREA = 2.0            # m^2: a smaller floor is degenerate, not a room
# m along a room's longer side, in its own axes (``render.room_frame_box``): the longest
# rooms of real homes (open-plan living-dining rooms of 3D-FRONT reach 12 m) with a margin
MAX_ROOM_SIDE = 16.0
MIN_VERTEX_SPACING = 1e-3       # m: consecutive vertices closer than this repeat each other
WALL_HEIGHT_RANGE = (1.8, 6.0)  # m, inclusive (also in room_layout.schema.json)
OPENING_TOLERANCE = 0.01        # m: an opening's centre and ends may miss its wall by this
MAX_WALL_THICKNESS = 0.5        # m: a house's two rooms whose walls stand back to back this
                                # close share that wall (real walls have a thickness)
CENTRE_OFF_FLOOR = 0.01         # m: an object's centre may lie this far outside the floor
SIZE_SLACK = 0.5                # a size within its category's ranges widened by half

# ---- walls and windows (``rules.walls``) ----------------------------------------------
# A back within 10 cm of the wall reads as against it: skirting boards, sockets and cables
# take a few centimetres, and the corpus leaves 0-4 cm; a hand's width (10 cm) is already a
# slot a designer sees.
WALL_CONTACT_GAP = 0.10
# A piece touches a wall (for a corner) when the wall runs within ``WALL_CONTACT_GAP`` of it
# over at least 0.25 m, so that grazing a wall's end at a corner does not count.
WALL_CONTACT_RUN = 0.25
# A gap narrower than the robot (0.4 m) behind a piece is dead space nobody can use or clean,
# so 10-40 cm off the wall is a near miss; from 0.4 m on the piece stands free on purpose.
NEAR_MISS = ROBOT_WIDTH
# The pieces a room is planned around, whose place mid-room a designer notices: wall
# categories of at least a washing machine's footprint (m^2). It takes in the pieces a design
# review found floating (pianos, fireplaces, TV stands, desks), every bed, sofa, storage unit,
# bath and shower, and leaves out the small fittings (nightstands, WC pans, shoe cabinets),
# which ``wall_contact`` holds to the wall.
LARGE_FOOTPRINT = 0.35
# Within a robot width of a wall a piece is at the wall (at worst a near miss: nothing can
# pass behind it); farther out it stands in the room.
FLOAT_WALL_GAP = ROBOT_WIDTH
# The widest gap the corpus's group placements leave between partners (a coffee table
# 0.35-0.5 m before a sofa; seats 0.02-0.2 m from desks; nightstands 0.02-0.06 m from beds).
GROUP_GAP = 0.5
# A seat turned more than 60 degrees away from a desk (its back or side to it) is not in a
# group with it; the corpus turns seats at most a few degrees off facing their desk.
GROUPED_SEAT_FACING = math.radians(60.0)
# A piece taller than the sill and within 20 cm of the glass stands in front of the window:
# it takes the light and puts the handle out of reach; farther out it stands beside the view.
WINDOW_ZONE_DEPTH = 0.20
# A quarter of a window's width is the most that may be hidden: a floor lamp or the corner of
# a wardrobe at the edge, not a wardrobe in front of it.
WINDOW_SHARE = 0.25

# ---- functional groups (``rules.groups``) ---------------------------------------------
# A seated person reaches about 0.6 m past the seat's front edge; the corpus puts chairs
# 0.02-0.2 m from a desk's front and 0.3-0.5 m from a coffee table's end.
SEAT_REACH = 0.6
# Half of a right angle: a seat turned further than this from its table is not seated at it.
SEATED_FACING = math.radians(45)
# A nightstand is within arm's reach of the pillow: the corpus leaves 2-6 cm, a designer up to
# about a hand's span more.
NIGHTSTAND_GAP = 0.3
# The pillow end of a bed: the first 0.6 m of its sides from the headboard (a nightstand is at
# most 0.5 m deep and stands with its back in line with the headboard).
HEAD_END = 0.6
# A bidet shares the toilet's plumbing wall, a step away; the corpus leaves 0.15-0.3 m.
BIDET_GAP = 0.6
# Two pieces on one wall line: parallel within this angle, backs within this offset.
SAME_LINE_ANGLE = math.radians(10)
SAME_LINE_OFFSET = 0.15
# Two walls make a corner when they meet at a real angle, not a slight bend of one wall.
CORNER_ANGLE = math.radians(60)
# From a sofa a TV is watched, and a coffee table reached, within about 5 m (the corpus puts
# the TV stand 1.2-5 m across from the sofa) and within 30 degrees of straight ahead (beyond
# that the head turns).
VIEW_RANGE = 5.0
VIEW_ANGLE = math.radians(30)
# Lounge seating serves a coffee table within about a metre (the corpus leaves 0.2-0.5 m).
LOUNGE_REACH = 1.0
# A TV on its stand is square to it: the corpus turns it by at most a few degrees.
TV_SQUARE = math.radians(10)
# A seat turned this much or more off the walls reads as left askew, not placed.
SQUARE_ANGLE = math.radians(15)

# ---- access and clearance (``rules.access``) ------------------------------------------
# A footprint that enters a strip by 2 cm or less, or a wall that does, leaves it clear: the
# corpus places neighbours 2 mm apart and synthesized rooms have a little yaw jitter, and a
# 2 cm overhang stops neither a drawer nor a robot.
CLEARANCE_TOLERANCE = 0.02
# Storage: 0.5 m is the least depth in front of wardrobe doors and drawers that lets them
# open and a person stand in front of them (design guides ask for 0.6-0.9 m).
STORAGE_CLEARANCE = 0.5
# Fixtures: the usual activity spaces of bathroom planning guides: 0.6 m in front of a WC or
# a bidet, 0.5 m in front of a washbasin, 0.6 m at a shower's entry, 0.5 m along the side of
# a bath from which one gets in.
FIXTURE_CLEARANCE = {'toilet': 0.6, 'bidet': 0.6, 'sink': 0.5, 'shower': 0.6, 'bathtub': 0.5}
# Where one gets in needs only part of the side clear: a shower door is about 0.6 m wide, and
# one steps into a bath somewhere along its long side, over a person's 0.6 m of shoulders.
ENTRY_STRETCH = {'shower': 0.6, 'bathtub': 0.6}
# Beds: the robot's width is the least useful gap beside a bed (the review's threshold), and
# 0.6 m of a side, a person's shoulders, is where one gets in.
BED_CLEARANCE = ROBOT_WIDTH
BED_STRETCH = 0.6
# Fronts a person uses: one should not face a wall closer than 0.3 m (a wardrobe's doors, a
# chair's knees, a toilet's user).
WALL_CLEARANCE = 0.3

# ---- the rooms of a home beyond the paper's (``rules.home``, ``corpus``) ----------------
# Kitchen planning (NKBA Kitchen Planning Guidelines): each leg of the sink-stove-fridge
# triangle 4 to 9 ft, the three together at most 26 ft; a work aisle 42 in (1.07 m) for one
# cook, of which the corpus keeps 1.0 m before the units.
TRIANGLE_LEG = (1.2, 2.7)
TRIANGLE_TOTAL = 7.9
KITCHEN_AISLE = 1.0
RUN_GAP = 0.05          # m between two units of one counter run
# m: how far a new unit's side may be from a neighbouring unit's for synthesis to slide it
# there (``rules.home.into_run``): about three of a kitchen image's pixels.
RUN_SNAP = 0.3
DOOR_SWING = 0.6        # m an appliance's or cabinet's door or flap needs before its front
# Dining: a chair needs 0.3 m behind it to be pulled out, and the table 0.75 m on a side
# where people sit (chair and pull-out; planning guides ask 0.75-0.9 m).
PULL_OUT = 0.3
DINING_CLEARANCE = 0.75
HALLWAY_PATH = 0.9      # m: the clear walking width of a hallway (accessible routes: 36 in)
