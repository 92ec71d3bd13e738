"""What has no DEM concept in it: Yade's value types (Vector3, Matrix3, Quaternion, ...) and its Serializable base."""
