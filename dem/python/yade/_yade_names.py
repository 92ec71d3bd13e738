"""The public names of Yade 2023.02a's modules, so that a name Talus lacks is reported as a Yade
name (in or out of Talus's scope) rather than as a typo. Produced by listing ``dir()`` of each module
under ``yade -n -x`` (its own names only: not what it imports), Debian's yade 2023.02a; "modules" are
the files of its package yade."""

NAMES = {
    "yade": """
        Aabb AlignedBox2 AlignedBox3 AttrFlags AxialGravityEngine BicyclePedalEngine Bo1_Box_Aabb
        Bo1_ChainedCylinder_Aabb Bo1_Cylinder_Aabb Bo1_DeformableElement_Aabb Bo1_Facet_Aabb
        Bo1_FluidDomainBbox_Aabb Bo1_GridConnection_Aabb Bo1_LevelSet_Aabb Bo1_Node_Aabb Bo1_PFacet_Aabb
        Bo1_Polyhedra_Aabb Bo1_Sphere_Aabb Bo1_Subdomain_Aabb Bo1_Tetra_Aabb Bo1_Wall_Aabb Body
        BodyContainer BodyIterator Bound BoundDispatcher BoundFunctor BoundaryController Box BoxFactory
        BubbleMat BubblePhys CapillarityEngine CapillaryCohesiveLaw CapillaryLaw
        CapillaryMindlinPhysDelaunay CapillaryParameters CapillaryPhys CapillaryPhysDelaunay
        CapillaryStressRecorder Cell CentralConstantAccelerationEngine CentralGravityEngine ChCylGeom6D
        ChainedCylinder ChainedState CircularFactory Clump CohFrictMat CohFrictPhys
        CohesiveDeformableElementMaterial CohesiveFrictionalContactLaw Collider CombinedKinematicEngine
        CpmMat CpmPhys CpmState CpmStateUpdater CundallStrackAdhesivePotential CundallStrackPotential
        CylScGeom CylScGeom6D Cylinder DeformableCohesiveElement DeformableElement
        DeformableElementMaterial DirecResearchEngine Disp2DPropLoadEngine Dispatcher DomainLimiter
        DragEngine ElastMat ElasticContactInteraction ElasticContactLaw ElasticMat EnergyTracker Engine
        EnumClass_BlinkHighlight FEInternalForceEngine Facet FacetTopologyAnalyzer FastMarchingMethod
        FieldApplier FileGenerator FlatGridCollider FlowEngine FlowEngineT FlowEngine_PeriodicInfo
        FluidDomainBbox FoamCoupling ForceContainer ForceEngine ForceRecorder ForceResetter FrictMat
        FrictMatCDM FrictPhys FrictViscoMat FrictViscoPhys Functor GLDrawCpmPhys
        GeneralIntegratorInsertionSortCollider GenericPotential GenericSpheresContact Gl1_Aabb Gl1_Box
        Gl1_ChainedCylinder Gl1_CpmPhys Gl1_Cylinder Gl1_DeformableElement Gl1_Facet Gl1_GridConnection
        Gl1_L3Geom Gl1_L6Geom Gl1_LevelSet Gl1_Node Gl1_NormPhys Gl1_PFacet Gl1_Polyhedra
        Gl1_PolyhedraGeom Gl1_PolyhedraPhys Gl1_PotentialParticle Gl1_Sphere Gl1_Tetra Gl1_Wall
        GlBoundDispatcher GlBoundFunctor GlExtraDrawer GlExtra_AlphaGraph GlExtra_LawTester
        GlExtra_OctreeCubes GlIGeomDispatcher GlIGeomFunctor GlIPhysDispatcher GlIPhysFunctor
        GlShapeDispatcher GlShapeFunctor GlStateDispatcher GlStateFunctor GlobalEngine
        GlobalStiffnessTimeStepper GranularMat GravityEngine GridCoGridCoGeom GridConnection GridNode
        GridNodeGeom6D HP1 HP2 HarmonicForceEngine HarmonicMotionEngine HarmonicRotationEngine
        HdapsGravityEngine HelixEngine HydroForceEngine HydrodynamicsLawLBM IGeom IGeomDispatcher
        IGeomFunctor IPhys IPhysDispatcher IPhysFunctor
        If2_2xLin4NodeTetra_LinCohesiveStiffPropDampElastMat If2_Lin4NodeTetra_LinIsoRayleighDampElast
        Ig2_Box_LevelSet_ScGeom Ig2_Box_Sphere_ScGeom Ig2_Box_Sphere_ScGeom6D
        Ig2_ChainedCylinder_ChainedCylinder_ScGeom Ig2_ChainedCylinder_ChainedCylinder_ScGeom6D
        Ig2_Facet_Polyhedra_PolyhedraGeom Ig2_Facet_Sphere_L3Geom Ig2_Facet_Sphere_ScGeom
        Ig2_Facet_Sphere_ScGeom6D Ig2_GridConnection_GridConnection_GridCoGridCoGeom
        Ig2_GridConnection_PFacet_ScGeom Ig2_GridNode_GridNode_GridNodeGeom6D
        Ig2_LevelSet_LevelSet_ScGeom Ig2_PFacet_PFacet_ScGeom Ig2_PP_PP_ScGeom
        Ig2_Polyhedra_Polyhedra_PolyhedraGeom Ig2_Polyhedra_Polyhedra_PolyhedraGeomOrScGeom
        Ig2_Polyhedra_Polyhedra_ScGeom Ig2_Sphere_ChainedCylinder_CylScGeom
        Ig2_Sphere_ChainedCylinder_CylScGeom6D Ig2_Sphere_GridConnection_ScGridCoGeom
        Ig2_Sphere_PFacet_ScGridCoGeom Ig2_Sphere_Polyhedra_ScGeom Ig2_Sphere_Sphere_L3Geom
        Ig2_Sphere_Sphere_L3Geom_Inc Ig2_Sphere_Sphere_L6Geom Ig2_Sphere_Sphere_L6Geom_Inc
        Ig2_Sphere_Sphere_ScGeom Ig2_Sphere_Sphere_ScGeom6D Ig2_Tetra_Tetra_TTetraGeom
        Ig2_Tetra_Tetra_TTetraSimpleGeom Ig2_Wall_LevelSet_ScGeom Ig2_Wall_PFacet_ScGeom
        Ig2_Wall_Polyhedra_PolyhedraGeom Ig2_Wall_Sphere_L3Geom Ig2_Wall_Sphere_L3Geom_Inc
        Ig2_Wall_Sphere_ScGeom InelastCohFrictMat InelastCohFrictPhys InsertionSortCollider Integrator
        Interaction InteractionContainer InteractionDispatchers InteractionGeometry
        InteractionGeometryDispatcher InteractionGeometryFunctor InteractionIterator InteractionLoop
        InteractionPhysics InteractionPhysicsDispatcher InteractionPhysicsFunctor
        InternalForceDispatcher InternalForceFunctor InterpolatingDirectedForceEngine
        InterpolatingHelixEngine InterpolatingSpiralEngine IntrCallback Ip2_2xCohFrictMat_CohFrictPhys
        Ip2_2xCohFrictMat_NormalInelasticityPhys Ip2_2xInelastCohFrictMat_InelastCohFrictPhys
        Ip2_BMP_BMP_CSPhys Ip2_BubbleMat_BubbleMat_BubblePhys Ip2_CohFrictMat_CohFrictMat_CohFrictPhys
        Ip2_CpmMat_CpmMat_CpmPhys Ip2_ElastMat_ElastMat_NormPhys Ip2_ElastMat_ElastMat_NormShearPhys
        Ip2_FrictMatCDM_FrictMatCDM_MindlinPhysCDM Ip2_FrictMat_CpmMat_FrictPhys
        Ip2_FrictMat_FrictMatCDM_MindlinPhysCDM Ip2_FrictMat_FrictMat_CapillaryLawPhys
        Ip2_FrictMat_FrictMat_CapillaryMindlinPhysDelaunay Ip2_FrictMat_FrictMat_CapillaryPhys
        Ip2_FrictMat_FrictMat_CapillaryPhysDelaunay Ip2_FrictMat_FrictMat_FrictPhys
        Ip2_FrictMat_FrictMat_KnKsPhys Ip2_FrictMat_FrictMat_LubricationPhys
        Ip2_FrictMat_FrictMat_MindlinCapillaryPhys Ip2_FrictMat_FrictMat_MindlinPhys
        Ip2_FrictMat_FrictMat_NormShearPhys Ip2_FrictMat_FrictMat_ViscoFrictPhys
        Ip2_FrictMat_FrictViscoMat_FrictViscoPhys Ip2_FrictMat_PolyhedraMat_FrictPhys
        Ip2_FrictViscoMat_FrictViscoMat_FrictViscoPhys Ip2_JCFpmMat_JCFpmMat_JCFpmPhys
        Ip2_LudingMat_LudingMat_LudingPhys Ip2_MortarMat_MortarMat_MortarPhys
        Ip2_PartialSatMat_PartialSatMat_MindlinPhys Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys
        Ip2_SimleViscoelasticMat_SimpleViscoelasticMat_SimpleViscoelasticPhys
        Ip2_ViscElCapMat_ViscElCapMat_ViscElCapPhys Ip2_ViscElMat_ViscElMat_ViscElPhys
        Ip2_WireMat_WireMat_WirePhys JCFpmMat JCFpmPhys JCFpmState JumpChangeSe3 KinemCNDEngine
        KinemCNLEngine KinemCNSEngine KinemCTDEngine KinemSimpleShearBox KinematicEngine KnKsPhys L3Geom
        L6Geom LBMbody LBMlink LBMnode Law2_ChCylGeom6D_CohFrictPhys_CohesionMoment
        Law2_CylScGeom6D_CohFrictPhys_CohesionMoment Law2_CylScGeom_FrictPhys_CundallStrack
        Law2_GridCoGridCoGeom_FrictPhys_CundallStrack Law2_L3Geom_FrictPhys_ElPerfPl
        Law2_L6Geom_FrictPhys_Linear Law2_PolyhedraGeom_PolyhedraPhys_Volumetric
        Law2_SCG_KnKsPhys_KnKsLaw Law2_ScGeom6D_CohFrictPhys_CohesionMoment
        Law2_ScGeom6D_InelastCohFrictPhys_CohesionMoment Law2_ScGeom_BubblePhys_Bubble
        Law2_ScGeom_CapillaryPhys_Capillarity Law2_ScGeom_CohFrictPhys_CohesionMoment
        Law2_ScGeom_CohFrictPhys_ElasticPlastic Law2_ScGeom_CpmPhys_Cpm Law2_ScGeom_FrictPhys_Basic
        Law2_ScGeom_FrictPhys_CundallStrack Law2_ScGeom_FrictViscoPhys_CundallStrackVisco
        Law2_ScGeom_ImplicitLubricationPhys Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM
        Law2_ScGeom_LudingPhys_Basic Law2_ScGeom_MindlinPhysCDM_HertzMindlinCDM
        Law2_ScGeom_MindlinPhys_HertzWithLinearShear Law2_ScGeom_MindlinPhys_Mindlin
        Law2_ScGeom_MindlinPhys_MindlinDeresiewitz Law2_ScGeom_MortarPhys_Lourenco
        Law2_ScGeom_NormalInelasticityPhys_NormalInelasticity Law2_ScGeom_PotentialLubricationPhys
        Law2_ScGeom_VirtualLubricationPhys Law2_ScGeom_ViscElCapPhys_Basic Law2_ScGeom_ViscElPhys_Basic
        Law2_ScGeom_ViscoFrictPhys_CundallStrack Law2_ScGeom_WirePhys_WirePM
        Law2_ScGridCoGeom_CohFrictPhys_CundallStrack Law2_ScGridCoGeom_FrictPhys_CundallStrack
        Law2_Spheres_Viscoelastic_SimpleViscoelastic Law2_TTetraSimpleGeom_NormPhys_Simple LawDispatcher
        LawFunctor LawTester LevelSet Lin4NodeTetra Lin4NodeTetra_Lin4NodeTetra_InteractionElement
        LinCohesiveElasticMaterial LinCohesiveStiffPropDampElastMat LinExponentialPotential
        LinIsoElastMat LinIsoRayleighDampElastMat LinearDragEngine LubricationPDFEngine LubricationPhys
        LudingMat LudingPhys MPIBodyContainer MatchMaker Material MaterialContainer Matrix3 Matrix3c
        Matrix6 Matrix6c MatrixX MatrixXc MeasureCapStress MicroMacroAnalyser MindlinCapillaryPhys
        MindlinPhys MindlinPhysCDM MomentEngine MortarMat MortarPhys NewtonIntegrator Node NormPhys
        NormShearPhys NormalInelasticityLaw NormalInteraction NormalShearInteraction O Omega
        OpenGLRenderer OpenGLRenderingEngine PDFEngine PFacet ParallelEngine PartialEngine
        PartialSatClayEngine PartialSatClayEngineT PartialSatMat PartialSatState Peri3dController
        PeriIsoCompressor PeriTriaxController PeriodicEngine PeriodicFlowEngine PeriodicPythonRunner
        PhaseCluster Polyhedra PolyhedraGeom PolyhedraMat PolyhedraPhys PolyhedraSplitter
        PotentialParticle PotentialParticle2AABB PotentialParticleVTKRecorder PyRunner Quaternion
        RadialForceEngine Recorder RegularGrid ResetRandomPosition RockJointLawRelationships
        RotStiffFrictPhys RotationEngine RungeKuttaCashKarp54Integrator STLImporter ScGeom ScGeom6D
        ScGridCoGeom Scene Serializable ServoPIDController Shape SimpleElasticRelationships
        SimpleElasticRelationshipsWater SimpleShear SimpleViscoelasticMat SimpleViscoelasticPhys
        SnapshotEngine SpatialQuickSortCollider Sphere SpheresFactory SpiralEngine
        SpiralInteractionLocator2d SplitPolyMohrCoulomb SplitPolyTauMax State StepDisplacer Subdomain
        SumIntrForcesCb TTetraGeom TTetraSimpleGeom TagsWrapper TesselationWrapper Tetra Tetra2TetraBang
        TetraAABB TetraBang TetraLaw TetraMold TetraVolumetricLaw ThermalEngine ThermalState
        ThreeDTriaxialEngine TimeStepper TimingDeltas TorqueEngine TorqueRecorder TranslationEngine
        TriaxialCompressionEngine TriaxialStateRecorder TriaxialStressController TriaxialTest
        TwoPhaseFlowEngine TwoPhaseFlowEngineT UniaxialStrainer UnsaturatedEngine VTKRecorder Vector2
        Vector2c Vector2i Vector3 Vector3c Vector3i Vector4 Vector6 Vector6c Vector6i VectorX VectorXc
        ViscElCapMat ViscElCapPhys ViscElMat ViscElPhys ViscoFrictPhys Wall WireMat WirePhys WireState
        boot config ctypes deprecatedTypes dirs ef2_Spheres_Elastic_ElasticLaw export f files geom
        libVersions libstdcxx log minieigenHP pack plot plugin plugins remote root runtime system timing
        utils vectorize wrapper yade ymport
    """.split(),
    "yade.export": """
        VTKExporter VTKWriter gmshGeo text text2vtk text2vtkSection textClumps textExt textPolyhedra
    """.split(),
    "yade.geom": """
        facetBox facetBunker facetCone facetCylinder facetCylinderConeGenerator facetHelix
        facetParallelepiped facetPolygon facetPolygonHelixGenerator facetSphere
    """.split(),
    "yade.pack": """
        Predicate PredicateBoolean PredicateDifference PredicateIntersection
        PredicateSymmetricDifference PredicateUnion SpherePack SpherePackIterator
        SpherePack_toSimulation cloudBestFitOBB filterSpherePack gtsSurface2Facets gtsSurfaceBestFitOBB
        hexaNet inAlignedBox inConvexPolyhedron inCylinder inEllipsoid inGtsSurface inGtsSurface_py
        inHalfSpace inHyperboloid inParallelepiped inSpace inSphere notInNotch randomDensePack
        randomPeriPack regularHexa regularOrtho revolutionSurfaceMeridians sweptPolylines2gtsSurface
    """.split(),
    "yade.plot": """
        LineRef addAutoData addData addDataColumns addImgData addPointTypeSpecifier afterCurrentAlpha
        autozoom axesWd componentSeparator componentSuffixes createPlots createTitleFrame currLineRefs
        current data imgData labels legendLoc live liveForceAlwaysUpdate liveInterval liveTimeStamp
        liveUpdate plotSyncLock plots reset resetData reverseData saveDataTxt saveGnuplot
        savePlotSequence savePylab scatterMarkerKw scientific setLiveForceAlwaysUpdate splitData
        tuplifyYAxis xlateLabel xylabels
    """.split(),
    "yade.timing": """
        reset stats
    """.split(),
    "yade.utils": """
        NormalRestitution2DampingRate PWaveTimeStep RayleighWaveTimeStep SpherePWaveTimeStep
        TableParamReader TetrahedronCentralInertiaTensor TetrahedronInertiaTensor
        TetrahedronSignedVolume TetrahedronVolume TetrahedronWithLocalAxesPrincipal aabbDim aabbExtrema
        aabbExtrema2d aabbWalls angularMomentum approxSectionArea avgNumInteractions
        bodyNumInteractionsHistogram bodyStressTensors box calm cart2spher clumpTemplate
        coordsAndDisplacements createInteraction defaultEngines defaultMaterial distApproxRose
        distApproxSE distIniClump distIniSE encodeVideoFromFrames fabricTensor facet facetBox
        facetCylinder flipCell forcesOnCoordPlane forcesOnPlane fractionalBox getBodyIdsContacts
        getCapillaryStress getDepthProfiles getDepthProfiles_center getDynamicStress getSpheresMass
        getSpheresVolume getSpheresVolume2D getStress getStressAndTangent getStressProfile
        getStressProfile_contact getTotalDynamicStress getViscoelasticFromSpheresInteraction
        growParticle growParticles highlightNone initMPI inscribedCircleCenter insideClump
        interactionAnglesHistogram intrsOfEachBody kineticEnergy levelSetBody loadVars lsSimpleShape
        makeVideo maxOverlapRatio momentum nGP negPosExtremeIds normalShearStressTensors
        numIntrsOfEachBody perpendicularArea phiIniCppPy phiIniPy plotDirections
        plotNumInteractionsHistogram pointInsidePolygon polyhedron porosity psd ptInAABB randomColor
        randomOrientation randomizeColors readParamsFromTable replaceCollider runningInBatch saveVars
        scalarOnColorScale setBodyAngularVelocity setBodyColor setBodyOrientation setBodyPosition
        setBodyVelocity setContactFriction setNewVerticesOfFacet setRefSe3 shiftBodies spher2cart sphere
        spiralProject stressTensorOfPeriodicCell sumFacetNormalForces sumForces sumTorques tetra
        tetraPoly totalForceInVolume trackPerfomance typedEngine unbalancedForce uniaxialTestFeatures
        vmData voidratio2D voxelPorosity voxelPorosityTriaxial waitIfBatch wall wireAll wireNoSpheres
        wireNone xMirror
    """.split(),
    "yade.ymport": """
        blockMeshDict ele gengeo gengeoFile gmsh iges polyMesh readPolyMesh stl text textClumps textExt
        textFacets textPolyhedra unv
    """.split(),
    "modules": """
        FEMxDEM WeightedAverage2d bf bisectionDecomposition bodiesHandling boot coloring config deformableelementsutils domaindecomposition export geom gridpfacet libVersions linterpolation log math minieigenHP mpy pack params plot polyhedra_utils post2d potential_utils qt remote runtime system timing utils wrapper ymport
    """.split(),
}
