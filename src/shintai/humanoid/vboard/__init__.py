"""vboard"""
