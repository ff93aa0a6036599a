"""unicycle"""
