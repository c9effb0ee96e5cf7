"""jackpy.ui"""
