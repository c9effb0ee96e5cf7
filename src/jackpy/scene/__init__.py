"""jackpy.scene"""
