def match_arm(figure, goal, cols):
    return None
