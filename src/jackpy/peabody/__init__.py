"""jackpy.peabody"""
